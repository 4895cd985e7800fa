#include "jobs/farm_merge.h"

#include <set>

#include "io/atomic_file.h"
#include "jobs/contact_sheet.h"
#include "util/version.h"

namespace seasim {

namespace {

std::string whyMissing(const ItemState& s) {
  switch (s.status) {
    case ItemState::Status::Failed:
      return "failed: " + s.detail.substr(0, s.detail.find('\n'));
    case ItemState::Status::Damaged:
      return "damaged: " + s.detail;
    case ItemState::Status::Missing:
      return "not rendered";
    case ItemState::Status::Done:
      return "done";
  }
  return "";
}

}  // namespace

MergeResult mergeFarmJob(const Job& job) {
  MergeResult result;
  const std::vector<ItemState> states = readItemStates(job, job.output_dir, true);
  result.total = static_cast<int>(states.size());
  nlohmann::json items = itemsJson(job, states);
  std::set<std::string> devices;
  double wall_total = 0;
  for (size_t i = 0; i < states.size(); ++i) {
    const ItemState& s = states[i];
    nlohmann::json& item = items[i];
    if (s.status == ItemState::Status::Done) {
      wall_total += s.wall_ms;
      if (item.contains("device") && item["device"].contains("label"))
        devices.insert(item["device"]["label"].get<std::string>());
    } else {
      result.missing.push_back(s);
      item["error"] = s.status == ItemState::Status::Failed ? s.detail : whyMissing(s);
    }
  }
  const bool complete = result.missing.empty();
  nlohmann::json missing = nlohmann::json::array();
  for (const ItemState& s : result.missing) missing.push_back(s.name);
  const nlohmann::json summary = {{"seasim", {{"version", version()}, {"git_commit", gitCommit()}}},
                                  {"job", job.name},
                                  {"job_file", job.file},
                                  {"output_dir", job.output_dir},
                                  {"complete", complete},
                                  {"items_total", result.total},
                                  {"items_done", result.total - static_cast<int>(result.missing.size())},
                                  {"missing", missing},
                                  {"wall_ms_total", wall_total},
                                  {"devices", devices},
                                  {"items", items}};
  result.report = job.output_dir + "/farm/report.json";
  result.contact_sheet = job.output_dir + "/farm/contact_sheet.html";
  writeTextAtomic(result.contact_sheet, contactSheetHtml(job, items, complete, "../", "seasim farm merge"));
  writeTextAtomic(result.report, summary.dump(2) + "\n");  // last: its "complete" covers the sheet too
  return result;
}

std::string missingItemsMessage(const MergeResult& r) {
  std::string msg = std::to_string(r.missing.size()) + " of " + std::to_string(r.total) + " items are missing:";
  for (const ItemState& s : r.missing) msg += "\n  " + s.name + " (" + whyMissing(s) + ")";
  return msg;
}

}  // namespace seasim
