#include "gvdp/io/stats.h"

#include <fstream>
#include <nlohmann/json.hpp>

#include "gvdp/base/error.h"
#include "gvdp/base/gpu.h"

namespace gvdp {

std::string statsJson(const SequenceOptions& o, const std::vector<FrameStats>& frames) {
  nlohmann::json j;
  j["scene"] = o.scene;
  j["movement"] = movementName(o.movement);
  j["backend"] = backendName(o.scheduler.backend);
  j["scheduler"] = schedulerName(o.scheduler.kind);
  j["width"] = o.width;
  j["height"] = o.height;
  j["levels"] = o.levels;
  if (o.scheduler.backend == Backend::Cuda) j["device"] = cudaDeviceSummary();
  nlohmann::json list = nlohmann::json::array();
  for (const FrameStats& f : frames)
    list.push_back({{"index", f.index}, {"ms", f.ms}, {"unfinished_pixels", f.unfinishedPixels}});
  j["frames"] = list;
  return j.dump(1);
}

void writeStatsJson(const std::string& path, const SequenceOptions& o,
                    const std::vector<FrameStats>& frames) {
  std::ofstream out(path);
  GVDP_INPUT_CHECK(out.good(), "cannot write '", path, "'");
  out << statsJson(o, frames) << "\n";
  GVDP_INPUT_CHECK(out.good(), "cannot write '", path, "'");
}

}  // namespace gvdp
