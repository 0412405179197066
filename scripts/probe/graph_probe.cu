// Does compute-sanitizer run a CUDA graph with a conditional WHILE node under each tool?
// argv[1]: 0 = WHILE node set from the device (as gvdp's graph scheduler), 1 = plain graph.
#include <cstdio>
#include <cstdlib>
#define CK(x)                                        \
  do {                                               \
    cudaError_t e = (x);                             \
    if (e != cudaSuccess) {                          \
      printf("%s: %s\n", #x, cudaGetErrorString(e)); \
      exit(1);                                       \
    }                                                \
  } while (0)

__global__ void body(unsigned* counter) {
  __shared__ unsigned s[128];
  s[threadIdx.x] = threadIdx.x;
  __syncthreads();
  if (threadIdx.x == 0) atomicAdd(counter, s[127]);
}
__global__ void control(unsigned* counter, cudaGraphConditionalHandle h) {
  if (*counter >= 127u * 5) cudaGraphSetConditional(h, 0);
}

int main(int argc, char** argv) {
  int mode = argc > 1 ? atoi(argv[1]) : 0;
  unsigned* counter;
  CK(cudaMalloc(&counter, 4));
  CK(cudaMemset(counter, 0, 4));
  cudaGraph_t graph;
  CK(cudaGraphCreate(&graph, 0));
  cudaStream_t stream;
  CK(cudaStreamCreateWithFlags(&stream, cudaStreamNonBlocking));
  if (mode == 0) {
    cudaGraphConditionalHandle h;
    CK(cudaGraphConditionalHandleCreate(&h, graph, 1, cudaGraphCondAssignDefault));
    cudaGraphNodeParams p{};
    p.type = cudaGraphNodeTypeConditional;
    p.conditional.handle = h;
    p.conditional.type = cudaGraphCondTypeWhile;
    p.conditional.size = 1;
    cudaGraphNode_t node;
    CK(cudaGraphAddNode(&node, graph, nullptr, nullptr, 0, &p));
    cudaGraph_t bodyGraph = p.conditional.phGraph_out[0];
    CK(cudaStreamBeginCaptureToGraph(stream, bodyGraph, nullptr, nullptr, 0,
                                     cudaStreamCaptureModeRelaxed));
    body<<<4, 128, 0, stream>>>(counter);
    control<<<1, 1, 0, stream>>>(counter, h);
    CK(cudaStreamEndCapture(stream, &bodyGraph));
  } else {
    CK(cudaStreamBeginCaptureToGraph(stream, graph, nullptr, nullptr, 0,
                                     cudaStreamCaptureModeRelaxed));
    body<<<4, 128, 0, stream>>>(counter);
    CK(cudaStreamEndCapture(stream, &graph));
  }
  cudaGraphExec_t exec;
  CK(cudaGraphInstantiate(&exec, graph, 0));
  CK(cudaGraphLaunch(exec, nullptr));
  unsigned v = 0;
  CK(cudaMemcpy(&v, counter, 4, cudaMemcpyDeviceToHost));
  printf("graph probe mode %d: counter %u (expected %u)\n", mode, v,
         mode == 0 ? 127u * 4 * 2 : 127u * 4);
  return 0;
}
