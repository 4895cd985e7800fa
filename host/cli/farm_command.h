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

// `seasim farm local-cluster start|stop|env DIR`: a private single-node Slurm (munged, slurmctld,
// slurmd) with every file under DIR, so `farm slurm --submit` can be tried on one machine. Runs the
// shipped slurm_localhost.sh (installed under share/seasim/tools; tests/farm/ in the source tree),
// the one the farm test uses; its exit code is returned (77: cannot run here, e.g. not root).
int cmdFarmLocalCluster(const std::string& action, const std::string& dir);

}  // namespace seasim
