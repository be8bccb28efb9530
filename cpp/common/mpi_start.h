// How the process starts MPI when nothing launched it.
//
// A process not started by a launcher (mpirun, mpiexec, srun) is an Open MPI
// singleton, one process on its own. By default Open MPI 4.1 still starts
// what only a job of several processes needs: a runtime daemon beside it,
// for processes it might spawn, and the network layers (UCX, OFI) it probes
// for the interconnect. That costs 0.3 s of MPI_Init on the reference
// machine, a fifth of the whole demo run, for nothing a single process uses.
// A singleton is therefore told (through Open MPI's own environment
// settings, set before MPI_Init and never over the user's) to run isolated,
// with the point-to-point layer ob1 over the self transport alone (it has
// no peer to share memory with): MPI_Init takes 0.03 s. And it makes no
// session directory: every isolated singleton would use the same one
// (/tmp/ompi.<host>.<uid>/jf.0/1/0), and one that ends removes it under
// another that starts, whose MPI_Init then fails ("orte_session_dir
// failed": runs started side by side, as scripts/studies.py does).
// Processes a launcher started are left alone.
#pragma once

namespace pushout::mpi
{
/// Call before MPI_Init (PetscInitialize). Sets, unless set already,
/// OMPI_MCA_ess_singleton_isolated=1, OMPI_MCA_pml=ob1, OMPI_MCA_btl=self
/// and OMPI_MCA_orte_create_session_dirs=0 when no launcher's variables
/// (OMPI_COMM_WORLD_SIZE, PMIX_RANK, PMI_RANK, PMI_SIZE, SLURM_PROCID) are in
/// the environment.
void prepare_singleton_start();
} // namespace pushout::mpi
