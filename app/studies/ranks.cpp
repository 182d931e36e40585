#include "app/studies/ranks.h"

#include "app/io/output.h"
#include "app/io/text.h"

#include "continuum/cylinder.h"

#include <mpi.h>

#include <string>

namespace demvv
{
void on_rank_zero_for_all(bool every_rank, const std::function<void()> &claim)
{
  if (!every_rank)
  {
    claim();
    return;
  }
  int code = 0;
  std::string message;
  if (continuum::parallel_info().rank == 0)
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
  MPI_Bcast(&code, 1, MPI_INT, 0, MPI_COMM_WORLD);
  MPI_Bcast(&length, 1, MPI_INT, 0, MPI_COMM_WORLD);
  message.resize(static_cast<std::size_t>(length));
  MPI_Bcast(message.data(), length, MPI_CHAR, 0, MPI_COMM_WORLD);
  if (code == 4)
    throw OutputError(message);
  if (code != 0)
    throw DeckError(message);
}
} // namespace demvv
