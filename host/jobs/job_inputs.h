// job_inputs.h — the checks of a job's input files that can be made before anything renders:
// each item's scene images (scene/scene_inputs.h) and its reference image (decodes, same size as
// the render). Run by `seasim validate` and at job start; an item that fails is reported with its
// error and not rendered, the others go on.
#pragma once
#include <map>
#include <string>
#include <vector>

#include "jobs/job.h"

namespace seasim {

// Item name -> the error that stops it (file:line: key '...': ...); empty when every item is fine.
std::map<std::string, std::string> checkJobInputs(const std::vector<RenderItem>& items);

}  // namespace seasim
