#pragma once
/// \file parallel.h
/// Loops over independent items on several threads, with the standard library's threads only
/// (docs/threads.md says why not oneTBB).
///
/// Two loops, both deterministic in what they compute: an item's work must not depend on which
/// thread runs it or in which order (each writes only its own slots of the output, or a per-thread
/// scratch that is merged afterwards in chunk order), and then the results are the same bytes for
/// any thread count.
/// - `parallel_for(n, threads, fn)`: static contiguous chunks, `fn(begin, end, chunk)`; chunk t
///   gets items [n t / T, n (t + 1) / T) with T = the threads used. For many cheap items (points,
///   faces): no synchronisation per item, and per-chunk results can be concatenated in chunk order.
/// - `parallel_items(n, threads, fn)`: each thread takes the next item from a shared counter,
///   `fn(item, worker)`. For few expensive items of uneven cost (distance fields).
///
/// Threads are started per call (tens of microseconds each); with one thread, or one item, the
/// loop runs on the calling thread. When `fn` throws, the other threads stop taking work, the
/// loop waits for them and rethrows the exception of the lowest chunk (`parallel_for`) or the
/// first one caught (`parallel_items`).
///
/// \code
///   std::vector<double> out(points.size());
///   edgefront::parallel_for(points.size(), threads, [&](size_t begin, size_t end, unsigned) {
///     for (size_t i = begin; i < end; ++i) out[i] = work(points[i]);
///   });
/// \endcode

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "edgefront/error.h"

namespace edgefront {

/// The threads the machine runs at once (`std::thread::hardware_concurrency`), at least 1.
inline unsigned default_threads() {
  const unsigned n = std::thread::hardware_concurrency();
  return n == 0 ? 1u : n;
}

/// The largest `threads` option accepted: far beyond any machine's cores, low enough that a typo
/// (or a negative number cast to unsigned) is refused instead of starting millions of threads.
inline constexpr unsigned kMaxThreads = 4096;

/// The thread count a `threads` option stands for: 0 means `default_threads()`, any other value
/// is taken as given. Every parallel loop resolves its option here.
/// \throws InvalidInput for more than `kMaxThreads`.
inline unsigned resolve_threads(unsigned threads) {
  if (threads > kMaxThreads) {
    throw InvalidInput("threads must be at most " + std::to_string(kMaxThreads) + " (0: all cores; got " +
                       std::to_string(threads) + ")");
  }
  return threads == 0 ? default_threads() : threads;
}

/// The threads `parallel_for` and `parallel_items` use for `n` items and the option `threads`
/// (0: all cores): `min(resolve_threads(threads), n)`, at least 1.
inline unsigned threads_for(std::size_t n, unsigned threads) {
  const std::size_t t = std::min<std::size_t>(resolve_threads(threads), n);
  return t == 0 ? 1u : static_cast<unsigned>(t);
}

/// Runs `fn(begin, end, chunk)` over [0, n) cut into `threads_for(n, threads)` contiguous chunks,
/// chunk t = [n t / T, n (t + 1) / T), one thread per chunk (chunk 0 on the calling thread).
/// \param n        number of items (0: nothing runs)
/// \param threads  threads to use; 0 = all cores (`default_threads()`)
/// \param fn       callable `void(std::size_t begin, std::size_t end, unsigned chunk)`
/// \throws whatever `fn` throws (the exception of the lowest chunk that threw), after every
///         thread has finished.
template <class Fn>
void parallel_for(std::size_t n, unsigned threads, Fn&& fn) {
  if (n == 0) return;
  const unsigned t = threads_for(n, threads);
  if (t == 1) {
    fn(std::size_t{0}, n, 0u);
    return;
  }
  std::vector<std::exception_ptr> errors(t);
  auto run = [&](unsigned c) {
    try {
      fn(n * c / t, n * (c + 1) / t, c);
    } catch (...) {
      errors[c] = std::current_exception();
    }
  };
  {
    std::vector<std::jthread> pool;
    pool.reserve(t - 1);
    for (unsigned c = 1; c < t; ++c) pool.emplace_back(run, c);
    run(0);
  }  // joins
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
}

/// Runs `fn(item, worker)` for every item in [0, n) on `threads_for(n, threads)` threads, each
/// taking the next unclaimed item (in increasing order) when it is free; worker 0 is the calling
/// thread. After an exception, or when `fn` returns false, no further item is started.
/// \param n        number of items
/// \param threads  threads to use; 0 = all cores
/// \param fn       callable `bool(std::size_t item, unsigned worker)`: true to go on, false to stop
///                 (the items already running finish)
/// \return true when every item ran, false when `fn` stopped the loop
/// \throws the first exception `fn` threw, after every thread has finished.
template <class Fn>
bool parallel_items(std::size_t n, unsigned threads, Fn&& fn) {
  if (n == 0) return true;
  const unsigned t = threads_for(n, threads);
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto run = [&](unsigned worker) {
    try {
      while (!stop.load(std::memory_order_relaxed)) {
        const std::size_t item = next.fetch_add(1, std::memory_order_relaxed);
        if (item >= n) return;
        if (!fn(item, worker)) stop.store(true, std::memory_order_relaxed);
      }
    } catch (...) {
      stop.store(true, std::memory_order_relaxed);
      const std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
    }
  };
  {
    std::vector<std::jthread> pool;
    pool.reserve(t - 1);
    for (unsigned w = 1; w < t; ++w) pool.emplace_back(run, w);
    run(0);
  }  // joins
  if (error) std::rethrow_exception(error);
  return !stop.load();
}

}  // namespace edgefront
