// How idle OpenMP threads wait, for every executable that runs the engine.
//
// Threads that finish a parallel loop early wait for the others.  libgomp's
// default is to spin for a long while (300 000 spins) before sleeping; when
// another process competes for the cores, the spinning thread holds a core
// its late partner needs, and each of a step's joins waits for the
// scheduler: two threads ran up to 14 times slower than one beside a single
// compiler process on two cores.  So the engine's executables sleep at once
// (OMP_WAIT_POLICY=passive), which costs about 10 % on an idle machine (the
// wake-up at each join) and keeps a loaded one from collapsing; a short spin
// (GOMP_SPINCOUNT=1000) kept the idle speed but did not reliably cure the
// loaded case (BENCHMARKS.md).  The user's own choice (OMP_WAIT_POLICY or
// GOMP_SPINCOUNT) is kept.  libgomp reads its environment in its own
// initialiser, before main(); an executable's .preinit_array runs before
// any shared library's initialiser, so that is where the default is set.
// This file is compiled into each executable (not into a library, whose
// unreferenced objects the linker would drop).
#include <cstdlib>

namespace
{
void prefer_passive_openmp_waits(int, char **, char **)
{
  if (!std::getenv("OMP_WAIT_POLICY") && !std::getenv("GOMP_SPINCOUNT"))
    setenv("OMP_WAIT_POLICY", "passive", 0);
}
} // namespace

__attribute__((section(".preinit_array"), used)) static void (*const demvv_preinit)(int, char **, char **) =
  &prefer_passive_openmp_waits;
