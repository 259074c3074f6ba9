#include "apps/tune_shards.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <utility>

#include "apps/command_line.h"
#include "apps/commit.h"
#include "apps/shard_files.h"
#include "core/input_error.h"
#include "io/csv_fields.h"
#include "io/reference_file.h"
#include "solver/optimizer_options.h"

namespace ipstep {
namespace tune {
namespace {

// The columns of --tune_output, in order.
const char* const kColumns[] = {
    "integrator", "optimizer", "adaptive",   "dt",      "tolerance",   "error_tolerance",
    "steps",      "failed",    "iterations", "seconds", "error",       "role",
    "family",     "position",  "shard",      "target",  "out_of_time", "search"};
enum Column {
  kIntegrator,
  kOptimizer,
  kAdaptive,
  kDt,
  kTolerance,
  kErrorTolerance,
  kSteps,
  kFailed,
  kIterations,
  kSeconds,
  kError,
  kRole,
  kFamily,
  kPosition,
  kShard,
  kTarget,
  kOutOfTime,
  kSearch
};

std::string Number17(double value) {
  char text[40];
  std::snprintf(text, sizeof(text), "%.17g", value);
  return text;
}

// A number of a shard file's row ("nan" too); an InputError naming the file.
double Field(const ShardRow& row, Column column) {
  const std::string& text = row.fields[column];
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size()) {
    throw InputError(
        "flag", "--merge",
        "'" + row.file + "': " + kColumns[column] + " '" + ClipInput(text) + "' is not a number");
  }
  return value;
}

// The results of a row into `c` (whose configuration comes from the search).
void ReadResults(const ShardRow& row, Candidate* c) {
  c->steps = static_cast<int>(Field(row, kSteps));
  c->failed = static_cast<int>(Field(row, kFailed));
  c->iterations = static_cast<long>(Field(row, kIterations));
  c->seconds = Field(row, kSeconds);
  c->error = Field(row, kError);
  c->shard = row.shard;
  c->role = row.fields[kRole];
}

// The row is the run of configuration `c` (not one of another search).
void CheckConfiguration(const ShardRow& row, const Candidate& c) {
  if (row.fields[kIntegrator] != c.integrator || row.fields[kOptimizer] != c.optimizer ||
      (row.fields[kAdaptive] == "1") != c.adaptive) {
    throw InputError("flag", "--merge",
                     "'" + row.file + "' (shard " + row.shard + "): the run of family " +
                         row.fields[kFamily] + ", position " + row.fields[kPosition] + " is " +
                         row.fields[kIntegrator] + " + " + row.fields[kOptimizer] +
                         ", the search's " + Label(c) + ": a file of another search");
  }
}

}  // namespace

std::string SearchKey(const std::string& scene, const std::string& measure, bool match_default,
                      const SearchSpace& space) {
  std::string integrators, optimizers;
  for (const std::string& name : space.integrators) {
    integrators += (integrators.empty() ? "" : "+") + name;
  }
  for (const std::string& name : space.optimizers) {
    optimizers += (optimizers.empty() ? "" : "+") + name;
  }
  return "scene=" + scene + ";measure=" + measure + ";at=" + Number17(space.t_end) +
         ";dt=" + Number17(space.dt) +
         ";target=" + (match_default ? std::string("match_default") : Number17(space.target)) +
         ";integrators=" + integrators + ";optimizers=" + optimizers;
}

std::string CsvHeader() {
  std::string header;
  for (const char* column : kColumns) header += (header.empty() ? "" : ",") + std::string(column);
  return header;
}

void WriteRows(const std::vector<Candidate>& rows, const SearchRecord& record, OutputFile* out) {
  std::ostream& stream = out->stream();
  stream.precision(10);
  stream << CsvHeader() << '\n';
  for (const Candidate& c : rows) {
    stream << c.integrator << ',' << c.optimizer << ',' << (c.adaptive ? 1 : 0) << ',' << c.dt
           << ',' << c.tolerance << ',' << c.error_tolerance << ',' << c.steps << ',' << c.failed
           << ',' << c.iterations << ',' << c.seconds << ',' << c.error << ',' << c.role << ','
           << c.family << ',' << c.position << ',' << c.shard << ',' << Number17(record.target)
           << ',' << (record.out_of_time ? 1 : 0) << ',' << CsvField(record.search) << '\n';
    out->EndRow();
  }
  out->Close();
}

MergedSearch ReadShards(const std::string& list, const std::string& search, SearchSpace* space) {
  const ShardFiles shards = ReadShardFiles(list);
  if (shards.header != CsvHeader()) {
    throw InputError("flag", "--merge",
                     "'" + shards.files.front() +
                         "' is not an ipstep_tune shard file of this version (its header is "
                         "not '" +
                         CsvHeader() + "')");
  }
  if (shards.rows.empty()) {
    throw InputError("flag", "--merge",
                     "'" + shards.files.front() +
                         "' and the others have no rows (every shard "
                         "writes at least its default row)");
  }
  MergedSearch out;
  out.files = shards.files.size();
  out.first_file = shards.files.front();
  out.shards = shards.count;
  // Every shard wrote its default row: a shard without rows is a missing one.
  for (int i = 0; i < shards.count; ++i) {
    const std::string shard = std::to_string(i) + "/" + std::to_string(shards.count);
    if (shards.shard_files.count(shard) == 0) {
      throw InputError("flag", "--merge",
                       "shard " + shard + " is missing (" +
                           std::to_string(shards.shard_files.size()) + " of " +
                           std::to_string(shards.count) + " shards among the files)");
    }
  }
  // One search: its key and one target (shard 0's; another shard's may differ
  // in round-off only, as with --match_default the target is a measurement).
  std::map<std::string, const ShardRow*> defaults;  // shard -> its default row
  bool have_target = false;
  for (const ShardRow& row : shards.rows) {
    if (row.fields[kSearch] != search) {
      throw InputError("flag", "--merge",
                       "'" + row.file + "' (shard " + row.shard + ") is from another search: '" +
                           ClipInput(row.fields[kSearch], 200) + "', not '" +
                           ClipInput(search, 200) + "' (give the shards' flags)");
    }
    if (row.fields[kRole] == "default") {
      if (!defaults.emplace(row.shard, &row).second) {
        throw InputError("flag", "--merge", "'" + row.file + "' has two default rows");
      }
    } else if (row.fields[kRole] != "search") {
      throw InputError("flag", "--merge",
                       "'" + row.file + "' has a row of role '" + ClipInput(row.fields[kRole]) +
                           "': a shard file has search and default rows only");
    }
    out.out_of_time = out.out_of_time || row.fields[kOutOfTime] == "1";
    const double target = Field(row, kTarget);
    if (row.index == 0 && !have_target) {
      space->target = target;
      have_target = true;
    }
  }
  for (const ShardRow& row : shards.rows) {
    const double target = Field(row, kTarget);
    if (!(std::abs(target - space->target) <= 1e-9 * std::abs(space->target))) {
      throw InputError("flag", "--merge",
                       "shard " + row.shard + " ('" + row.file + "') has the target " +
                           Number17(target) + ", shard 0/" + std::to_string(shards.count) + " " +
                           Number17(space->target));
    }
  }
  for (const auto& shard : shards.shard_files) {
    if (defaults.count(shard.first) == 0) {
      throw InputError("flag", "--merge", "'" + shard.second + "' has no default row");
    }
  }
  const ShardRow& fallback = *defaults.at("0/" + std::to_string(shards.count));
  out.fallback = DefaultCandidate(space->dt, space->t_end);
  CheckConfiguration(fallback, out.fallback);
  ReadResults(fallback, &out.fallback);
  // The runs, with their configurations from the search itself.
  std::map<std::pair<int, int>, Candidate> runs;
  std::vector<std::vector<Candidate>> families(space->families());
  for (const ShardRow& row : shards.rows) {
    if (row.fields[kRole] != "search") continue;
    const double family = Field(row, kFamily), position = Field(row, kPosition);
    const int f = static_cast<int>(family), k = static_cast<int>(position);
    if (family != f || f < 0 || f >= space->families()) {
      throw InputError("flag", "--merge",
                       "'" + row.file + "': family " + row.fields[kFamily] +
                           " is not one of the search's " + std::to_string(space->families()));
    }
    if (f % shards.count != row.index) {
      throw InputError("flag", "--merge",
                       "'" + row.file + "': family " + std::to_string(f) +
                           " does not belong to shard " + row.shard);
    }
    if (families[f].empty()) {
      std::vector<size_t> starts;
      families[f] = space->Family(f, &starts);
    }
    if (position != k || k < 0 || k >= static_cast<int>(families[f].size())) {
      throw InputError("flag", "--merge",
                       "'" + row.file + "': family " + std::to_string(f) + " has no position " +
                           row.fields[kPosition]);
    }
    Candidate c = families[f][k];
    CheckConfiguration(row, c);
    ReadResults(row, &c);
    if (!runs.emplace(std::make_pair(f, k), c).second) {
      throw InputError("flag", "--merge",
                       "'" + row.file + "': family " + std::to_string(f) + ", position " +
                           std::to_string(k) + " is twice");
    }
  }
  for (auto& run : runs) out.runs.push_back(std::move(run.second));
  return out;
}

ReferenceSolution SearchReference(const Scene& scene, const SimulationOptions& base,
                                  const ReferenceOptions& options, double dt, double t_end,
                                  const std::string& directory, const std::string& own_flags_file,
                                  bool* computed) {
  auto compute = [&] { return ComputeReference(scene, base, options, dt, t_end); };
  if (directory.empty()) {
    *computed = true;
    return compute();
  }
  // Every flag given that may change the scene or its runs (the search's own
  // flags and the logging's do not).
  std::string given;
  for (const auto& [name, value] : GivenFlags(own_flags_file)) given += " --" + name + "=" + value;
  // And what the flags do not say: a pinned contact stiffness
  // (sim/contact_kappa_pin.h).
  for (const auto& [effect, values] : base.effect_overrides) given += " " + effect + values.dump();
  const std::string key =
      "ipstep_tune reference|" + scene.name + "|" + given + "|" + options.integrator + "|" +
      OptimizerName(options.optimizer.optimizer) + "|" + Number17(options.optimizer.tolerance) +
      "|" + std::to_string(options.refinement) + "|" + std::to_string(options.checkpoints) + "|" +
      Number17(dt) + "|" + Number17(t_end) + "|" + IPSTEP_COMMIT;
  std::string line = key;  // the file's first line
  std::replace(line.begin(), line.end(), '\n', ' ');
  return CachedReference(directory, line, compute, computed);
}

}  // namespace tune
}  // namespace ipstep
