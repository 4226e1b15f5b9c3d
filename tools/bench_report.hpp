#pragma once
#include <ostream>
#include <string>
#include <vector>

#include "bench_runner.hpp"

namespace ssrcl::cli {

// Terminal table: one row per (input, configuration).
void printBenchTable(std::ostream& out, const std::vector<BenchResult>& results, const std::string& device);
// Everything measured, for machines.
void writeBenchJson(const std::string& path, const std::vector<BenchResult>& results, const std::string& device);
// Error (RMSE) against median device time, log-log, one colour per input, its Pareto front drawn.
void writeBenchSvg(const std::string& path, const std::vector<BenchResult>& results, const std::string& device,
                   const std::string& errorAxis = "RMSE against the reference preset (log)");

}  // namespace ssrcl::cli
