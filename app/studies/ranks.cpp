#include "app/studies/ranks.h"

#include "app/io/output.h"
#include "app/io/text.h"

#include <mpi.h>

#include <cstdlib>
#include <string>

namespace demvv
{
namespace
{
bool mpi_running()
{
  int initialised = 0, finalised = 0;
  MPI_Initialized(&initialised);
  MPI_Finalized(&finalised);
  return initialised && !finalised;
}

/// Open MPI's launcher (and PMI-based ones) tell each rank so.
bool launched_by_mpirun()
{
  for (const char *name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(name))
      return true;
  return false;
}
} // namespace

continuum::ParallelInfo study_ranks()
{
  if (mpi_running() || launched_by_mpirun())
    return continuum::parallel_info();
  return {0, 1};
}

void wait_for_all_ranks()
{
  if (mpi_running())
    MPI_Barrier(MPI_COMM_WORLD);
}

int largest_over_ranks(int value)
{
  if (mpi_running())
    MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  return value;
}

void on_rank_zero_for_all(bool every_rank, const std::function<void()> &claim)
{
  if (!every_rank)
  {
    claim();
    return;
  }
  int code = 0;
  std::string message;
  if (study_ranks().rank == 0)
    try
    {
      claim();
    }
    catch (const OutputError &e)
    {
      code = 4;
      message = e.what();
    }
    catch (const std::exception &e)
    {
      code = 2;
      message = e.what();
    }
  int length = static_cast<int>(message.size());
  if (mpi_running())
  {
    MPI_Bcast(&code, 1, MPI_INT, 0, MPI_COMM_WORLD);
    MPI_Bcast(&length, 1, MPI_INT, 0, MPI_COMM_WORLD);
    message.resize(static_cast<std::size_t>(length));
    MPI_Bcast(message.data(), length, MPI_CHAR, 0, MPI_COMM_WORLD);
  }
  if (code == 4)
    throw OutputError(message);
  if (code != 0)
    throw DeckError(message);
}
} // namespace demvv
