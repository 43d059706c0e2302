#include "util/cost_context.h"

#include <mutex>

namespace fenestra {
namespace {

std::mutex g_mutex;
CostContext g_process;  // guarded by g_mutex
thread_local bool t_set = false;
thread_local CostContext t_context;

}  // namespace

CostContext cost_context() {
  if (t_set) return t_context;
  std::lock_guard<std::mutex> lock(g_mutex);
  return g_process;
}

void set_cost_context(const CostContext& context) {
  std::lock_guard<std::mutex> lock(g_mutex);
  g_process = context;
}

CostScope::CostScope(const CostContext& context) : had_previous_(t_set), previous_(t_context) {
  t_set = true;
  t_context = context;
}

CostScope::~CostScope() {
  t_set = had_previous_;
  t_context = previous_;
}

}  // namespace fenestra
