#pragma once
// What the cost checks need to know besides the scene: the memory limit the user gave, if any,
// and what the scene is being loaded for (the checks made while a scene is read, before its
// opening domain is diced, refuse a domain whose matrices cannot fit only when they will be
// computed). Set process-wide by the command line, per call (per thread) by Python.
#include <cstdint>

namespace fenestra {

enum class CostCommand {
  Any,            // not known (a scene loaded from Python): assume the contributions
  Contributions,  // E, A, T and the path records
  Evaluate,       // a path-traced evaluation with cutters: no per-element matrices
  Solve,          // contributions, then the solver
  Solver,         // the solver alone, with contributions already computed
  Sky,            // the sky map only
  AnnualCutters,  // an annual study traced with the openings cut (annual --cutters): no records
};

struct CostContext {
  uint64_t max_memory = 0;  // bytes; 0: detect (memory_limit())
  CostCommand command = CostCommand::Any;
};

// The context in force on this thread: the innermost CostScope, else the process-wide one.
CostContext cost_context();
// Process-wide context (the command line sets it once, before loading the scene).
void set_cost_context(const CostContext& context);

// Sets the context for this thread while it lives (Python: one call).
class CostScope {
 public:
  explicit CostScope(const CostContext& context);
  ~CostScope();
  CostScope(const CostScope&) = delete;
  CostScope& operator=(const CostScope&) = delete;

 private:
  bool had_previous_;
  CostContext previous_;
};

// Whether the per-element matrices E, A and T will be computed for this command.
inline bool needs_element_matrices(CostCommand c) {
  return c == CostCommand::Any || c == CostCommand::Contributions || c == CostCommand::Solve ||
         c == CostCommand::Solver;
}

}  // namespace fenestra
