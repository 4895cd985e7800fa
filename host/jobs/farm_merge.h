// farm_merge.h — `seasim farm merge JOB`: after the shards, checks that every item of the job is in
// the shared results folder with files matching their checksums, and writes the job's summary:
// <output_dir>/farm/report.json (every item's status, timings, device and error) and
// <output_dir>/farm/contact_sheet.html (the items' PNGs on one page). Both are written in every
// case, atomically; report.json's "complete" is true only when every item is done and intact.
#pragma once
#include <string>
#include <vector>

#include "jobs/farm_items.h"
#include "jobs/job.h"

namespace seasim {

struct MergeResult {
  int total = 0;
  std::vector<ItemState> missing;  // every item not done and intact, with why
  std::string report, contact_sheet;
};

MergeResult mergeFarmJob(const Job& job);

// "3 of 10 items are missing: a (failed: ...), b (not rendered), c (damaged: ...)".
std::string missingItemsMessage(const MergeResult& result);

}  // namespace seasim
