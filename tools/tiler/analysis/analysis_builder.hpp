// `globe-tiler analyze`: a terrain package -> an analysis package with the
// same tiles, holding per-sample slope, aspect, curvature and sky-view factor computed from
// the heights of each zoom (so every zoom's analytics match the heights drawn
// at that zoom), and flow direction and accumulation solved over the whole
// finest zoom (flow/flow_solver.hpp) and carried to coarser zooms along the
// rivers. Neighbouring blocks supply the samples past each block's
// edges, so there are no seams; deterministic for any thread count;
// resumable (docs/analysis.md).
#pragma once

#include "kit/package_output.hpp"

#include <cstdint>
#include <string>
#include <vector>

#include "analysis/flow/flow_method.hpp"
#include "analysis/sky_view.hpp"
#include "kit/build_options.hpp"
#include "kit/progress.hpp"
#include "tileformat/analysis_block.hpp"

namespace globe {

struct AnalysisSettings : BuildOptions {
  std::vector<tileformat::AnalysisLayer> layers;  // ascending ids
  SkyViewSettings skyview;
  uint64_t memory_mb = 1024;  // the flow solver's working set (--memory-mb)
  int64_t flow_chunk = 0;     // the flow solver's chunk side (--flow-chunk); 0: chosen
  flow::FlowMethod flow_method = flow::FlowMethod::kFill;  // --flow-method
};

struct AnalysisSummary : PackageSummary {
  std::string flow_note;  // with the flow layers: how the solve went
};

// Throws InputError (not a terrain package, a corrupt tile: naming the file
// and tile), OutputError (cannot write).
AnalysisSummary build_analysis(const AnalysisSettings& settings, Progress& progress);

}  // namespace globe
