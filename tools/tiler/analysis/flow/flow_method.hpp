// How water crosses depressions and flats (--flow-method): fill them
// (priority-flood, flats and filled depressions routed; out of core), or
// carve through their rims (least-cost routing in height order from the
// data's edge; the whole grid in memory). docs/analysis.md "Flow methods".
#pragma once

namespace globe::flow {

enum class FlowMethod { kFill, kCarve };

}  // namespace globe::flow
