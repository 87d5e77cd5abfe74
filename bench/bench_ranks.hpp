// The benchmarks of a program run under mpirun (bench_distributed, bench_linear_solver's
// BM_Distributed): every process runs them, each of its iterations a collective step of all;
// only rank 0 reports.
#pragma once

#include <benchmark/benchmark.h>

#include <vector>

#include "iga/parallel/communicator.hpp"

namespace iga::bench {

/// Reports nothing (the processes but rank 0).
class Silent final : public benchmark::BenchmarkReporter {
 public:
  bool ReportContext(const Context&) override { return true; }
  void ReportRuns(const std::vector<Run>&) override {}
};

/// Runs the benchmarks benchmark::Initialize selected on every process, rank 0 reporting.
inline void run_on_every_rank() {
  if (world().root()) {
    benchmark::RunSpecifiedBenchmarks();
  } else {
    Silent silent;
    benchmark::RunSpecifiedBenchmarks(&silent);
  }
  benchmark::Shutdown();
}

}  // namespace iga::bench
