// farm_command.h — `seasim farm slurm|merge|status`: a job on a Slurm cluster (jobs/farm_*.h,
// docs/farm.md).
#pragma once
#include <string>

namespace seasim {

struct FarmSlurmCmd {
  std::string job, output_dir, partition, time_limit, device;
  int tasks = 0;
  int retries = 2;
  bool submit = false;
};
int cmdFarmSlurm(const FarmSlurmCmd& cmd);

int cmdFarmMerge(const std::string& job, const std::string& output_dir);

struct FarmStatusCmd {
  std::string job, output_dir;
  int tasks = 0;  // 0: from the folder's manifests and shard plans
  bool json = false;
};
int cmdFarmStatus(const FarmStatusCmd& cmd);

}  // namespace seasim
