// Which shared-memory accesses does compute-sanitizer's racecheck treat as synchronised? Warp 0
// writes 64 words, then raises a flag; warp 1 waits for the flag, then reads them. Each kernel
// uses one kind of access for the data and the flag; run under racecheck, a kernel whose name
// shows in a hazard report uses accesses the tool considers racing.
#include <cstdio>
#include <cstdlib>
#include <cuda/atomic>

using Ref = cuda::atomic_ref<unsigned, cuda::thread_scope_block>;

template <int Kind>
__global__ void probe(unsigned* out) {
  __shared__ unsigned data[64];
  __shared__ unsigned flag;
  if (threadIdx.x == 0) flag = 0;
  __syncthreads();
  int lane = threadIdx.x & 31, warp = threadIdx.x >> 5;
  if (warp == 0) {
    for (int i = lane; i < 64; i += 32) {
      if (Kind == 0) data[i] = i;                                        // plain
      if (Kind == 1) *(volatile unsigned*)&data[i] = i;                  // volatile
      if (Kind == 2) Ref(data[i]).store(i, cuda::memory_order_relaxed);  // st.relaxed.cta
      if (Kind == 3) atomicExch(&data[i], i);                            // atom
      if (Kind == 4) data[i] = i;  // plain data, release/acquire flag
    }
    __syncwarp();
    if (lane == 0) Ref(flag).store(1, cuda::memory_order_release);
  } else {
    if (lane == 0)
      while (Ref(flag).load(cuda::memory_order_acquire) == 0) __nanosleep(32);
    __syncwarp();
    unsigned s = 0;
    for (int i = lane; i < 64; i += 32) {
      if (Kind == 0 || Kind == 4) s += data[i];
      if (Kind == 1) s += *(volatile unsigned*)&data[i];
      if (Kind == 2) s += Ref(data[i]).load(cuda::memory_order_relaxed);
      if (Kind == 3) s += atomicAdd(&data[i], 0u);
    }
    out[lane] = s;
  }
}

int main(int argc, char** argv) {
  int kind = argc > 1 ? atoi(argv[1]) : 0;
  unsigned* out;
  cudaMalloc(&out, 32 * sizeof(unsigned));
  const char* names[] = {"plain", "volatile", "relaxed_cta", "atomic", "plain_with_release_flag"};
  switch (kind) {
    case 0:
      probe<0><<<1, 64>>>(out);
      break;
    case 1:
      probe<1><<<1, 64>>>(out);
      break;
    case 2:
      probe<2><<<1, 64>>>(out);
      break;
    case 3:
      probe<3><<<1, 64>>>(out);
      break;
    default:
      probe<4><<<1, 64>>>(out);
      break;
  }
  cudaDeviceSynchronize();
  printf("probe kind: %s\n", names[kind]);
  printf("done: %s\n", cudaGetErrorString(cudaGetLastError()));
}
