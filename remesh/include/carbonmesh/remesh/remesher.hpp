#pragma once
// The interval-constraining remesher of the reference dissertation (Algorithm 1): every edge length is driven
// into [emin, emax] while topology and shape are kept and valences are made regular.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "carbonmesh/remesh/mesh.hpp"
#include "carbonmesh/remesh/metrics.hpp"

namespace carbonmesh {

enum class ParametrizationWeights { MeanValue, ShapePreserving };

// One line of progress: the state after an iteration of Algorithm 1.
struct IterationLog {
  int iteration = 0;
  std::size_t long_edges = 0, short_edges = 0;
  double percent_regular = 0;
  double mean = 0, std = 0;  // edge length
  double seconds = 0;        // since the start of remesh()
  bool nonlinear = false;    // the nonlinear optimizer ran instead of the low-pass filter
};

struct RemeshSettings {
  double emin = 1.2, emax = 1.8;  // the constraining interval
  int iterations = 150;           // n: at most this many iterations
  int kl = 2;                     // star number of the low-pass filter
  int kn = 2;                     // star number of the nonlinear optimizer
  int p = 0;                      // replace the projection target by the current mesh every p iterations (0: never)
  double l = 0.5;                 // percent of long+short edges at or below which the nonlinear optimizer runs
  ParametrizationWeights weights = ParametrizationWeights::MeanValue;
  // Called after every iteration (progress lines, CSV logs). May be empty.
  std::function<void(const IterationLog&)> on_iteration;
};

struct RemeshResult {
  bool converged = false;  // no long and no short edge left
  int iterations = 0;
  bool post_processed = false;
  std::size_t long_edges = 0, short_edges = 0;
  double percent_regular = 0;
  double percent_eval_gt1 = 0;  // vertices with (ideal - valence)^2 > 1
  double seconds = 0;
  Topology before, after;  // the surface type (genus, components, borders) is kept: before.same_type(after)
  std::vector<IterationLog> log;
};

// Remeshes `mesh` in place. Throws InputError for an invalid interval (emin <= 0 or emin >= emax).
RemeshResult remesh(TriMesh& mesh, const RemeshSettings& settings);

nlohmann::json to_json(const RemeshResult& result);

}  // namespace carbonmesh
