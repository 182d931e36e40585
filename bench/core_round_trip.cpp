// demvv_core_round_trip: how long a cache line takes to go from one core to
// another and back on this machine, the price a thread pays for every
// ball, contact load or flag the other thread wrote last.
//
//   demvv_core_round_trip [TRIPS]
//
// Two threads (placed by the operating system, as demvv's OpenMP threads
// are) hand one atomic counter back and forth TRIPS times (default 100000)
// in eleven batches of at most half a second each, and print the median
// batch's time per round trip in nanoseconds:
//
//   core round trip 182.4 ns (batches 175.0-240.3 ns, up to 100000 trips or 0.5 s each)
//
// On a virtual machine the figure depends on where the host placed the
// virtual cores (one chiplet or two) and can change within an hour: the
// identical-work benchmark (identical_work.sh) prints it with every round,
// because a two-thread run's speed follows it.  A machine figure, never a
// test: the smoke test checks only that a line is printed.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <thread>
#include <vector>

namespace
{
/// The counter both threads hand back and forth, on a cache line of its own.
struct alignas(64) Baton
{
  std::atomic<long> value{0};
  std::atomic<bool> done{false};
};

/// The partner: answers each odd value with the next even one until done.
void answer(Baton &baton)
{
  long seen = 0;
  while (!baton.done.load(std::memory_order_relaxed))
  {
    const long v = baton.value.load(std::memory_order_acquire);
    if (v != seen && v % 2 == 1)
    {
      baton.value.store(v + 1, std::memory_order_release);
      seen = v;
    }
  }
}

/// Nanoseconds per round trip over at most `trips` round trips and at most
/// half a second (a machine whose other core is busy may take milliseconds
/// a trip): this thread sets odd values, the partner answers.
double batch(Baton &baton, long trips, long &next)
{
  using clock = std::chrono::steady_clock;
  const auto start = clock::now(), deadline = start + std::chrono::milliseconds(500);
  long done = 0;
  while (done < trips && (done % 256 != 0 || clock::now() < deadline))
  {
    baton.value.store(next + 1, std::memory_order_release);
    while (baton.value.load(std::memory_order_acquire) != next + 2)
    {
    }
    next += 2;
    ++done;
  }
  return 1e9 * std::chrono::duration<double>(clock::now() - start).count() / double(done);
}
} // namespace

int main(int argc, char **argv)
{
  const long trips = argc > 1 ? std::atol(argv[1]) : 100000;
  if (trips < 1 || argc > 2)
  {
    std::fprintf(stderr, "usage: demvv_core_round_trip [TRIPS]  (TRIPS a positive integer, default 100000)\n");
    return 2;
  }
  constexpr int batches = 11;
  Baton baton;
  std::thread partner(answer, std::ref(baton));
  long next = 0;
  std::vector<double> ns(batches);
  for (double &t : ns)
    t = batch(baton, trips, next);
  baton.done.store(true, std::memory_order_relaxed);
  partner.join();
  std::sort(ns.begin(), ns.end());
  std::printf("core round trip %.1f ns (batches %.1f-%.1f ns, up to %ld trips or 0.5 s each)\n", ns[batches / 2],
              ns.front(), ns.back(), trips);
  return 0;
}
