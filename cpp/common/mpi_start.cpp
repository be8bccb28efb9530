#include "mpi_start.h"
#include <cstdlib>
#include <initializer_list>

namespace pushout::mpi
{
void prepare_singleton_start()
{
  for (const char* launched :
       {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE", "SLURM_PROCID"})
    if (std::getenv(launched))
      return;
  // The last argument 0: a value the user set stays.
  setenv("OMPI_MCA_ess_singleton_isolated", "1", 0);
  setenv("OMPI_MCA_pml", "ob1", 0);
  setenv("OMPI_MCA_btl", "self", 0);
  setenv("OMPI_MCA_orte_create_session_dirs", "0", 0);
}
} // namespace pushout::mpi
