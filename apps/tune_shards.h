// ipstep_tune's rows (--tune_output), its shards and its reference file
// (apps/tune_program.cc). A shard (--shard=i/N) runs the families f of the
// search with f % N == i (apps/tune_search.h) and writes their rows and the
// default configuration's; --merge reads the shards' files back
// (apps/shard_files.h), checks that they are one search's whole set, and
// hands the runs, in the unsharded search's order, to the same choice.
#pragma once

#include <string>
#include <vector>

#include "apps/tune_search.h"
#include "io/output_file.h"
#include "sim/reference.h"

namespace ipstep {
namespace tune {

// What every row of one process says about its search.
struct SearchRecord {
  std::string search;  // SearchKey
  double target = 0.0;
  bool out_of_time = false;  // the budget ran out
};

// The key of a search: the scene, measure, end time, step, target (or
// "match_default"), integrators and optimisers. Shards of one search have
// one key; the merge refuses others.
std::string SearchKey(const std::string& scene, const std::string& measure, bool match_default,
                      const SearchSpace& space);

// The CSV header of --tune_output and the rows: one per run, numbers to 10
// digits (the target to 17).
std::string CsvHeader();
void WriteRows(const std::vector<Candidate>& rows, const SearchRecord& record, OutputFile* out);

struct MergedSearch {
  std::vector<Candidate> runs;  // the runs of the search, by family and position
  Candidate fallback;           // the default configuration's run (shard 0's)
  bool out_of_time = false;     // some shard's budget ran out
  int shards = 0;
  size_t files = 0;
  std::string first_file;  // the first of the files, sorted
};

// --merge: the shard files of `list` of the search `search` in `space`
// (whose target it sets from the shards; the caller sets `within` after).
// An InputError naming --merge and the shard or the file for a missing or
// duplicated shard, a file of another search or program, and a row that
// does not belong (a family of another shard, a configuration the search
// does not have, twice the same run).
MergedSearch ReadShards(const std::string& list, const std::string& search, SearchSpace* space);

// The reference for the search: read from a file in `directory` (a
// reference file of io/reference_file.h, keyed by the commit, the
// reference's options, dt, t_end and every flag given that the search does
// not own, i.e. not defined in `own_flags_file`) when there is one; else
// computed, and written there (an empty directory: not kept). Processes that
// need the same reference at once compute it once. `computed`: whether this
// one did.
ReferenceSolution SearchReference(const Scene& scene, const SimulationOptions& base,
                                  const ReferenceOptions& options, double dt, double t_end,
                                  const std::string& directory, const std::string& own_flags_file,
                                  bool* computed);

}  // namespace tune
}  // namespace ipstep
