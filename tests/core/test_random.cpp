#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <mutex>
#include <set>
#include <thread>
#include <vector>

#include "core/digest.h"
#include "core/parallel.h"
#include "core/random.h"

using namespace hairfit;

TEST_CASE("a stream depends only on (seed, stage, item)") {
  Random a(1, RandomStage::roots, 17), b(1, RandomStage::roots, 17);
  for (int i = 0; i < 100; ++i) CHECK(a.next_u64() == b.next_u64());
  Random c(2, RandomStage::roots, 17), d(1, RandomStage::clusters, 17), e(1, RandomStage::roots, 18);
  Random f(1, RandomStage::roots, 17);
  const std::uint64_t first = f.next_u64();
  CHECK(c.next_u64() != first);
  CHECK(d.next_u64() != first);
  CHECK(e.next_u64() != first);
}

TEST_CASE("uniform numbers have the moments of U[0,1)") {
  Random r(5, RandomStage::test, 0);
  const int n = 200000;
  double sum = 0, sum2 = 0, lo = 1, hi = 0;
  for (int i = 0; i < n; ++i) {
    const double u = r.uniform();
    sum += u;
    sum2 += u * u;
    lo = std::min(lo, u);
    hi = std::max(hi, u);
  }
  CHECK(lo >= 0.0);
  CHECK(hi < 1.0);
  // Standard errors: mean 1/sqrt(12 n) ≈ 6.5e-4; allow 5 sigma.
  CHECK(std::fabs(sum / n - 0.5) < 5 * 6.5e-4);
  CHECK(std::fabs(sum2 / n - 1.0 / 3.0) < 5e-3);
}

TEST_CASE("below(n) is uniform and in range") {
  Random r(9, RandomStage::test, 1);
  std::vector<int> counts(7, 0);
  for (int i = 0; i < 70000; ++i) {
    const auto k = r.below(7);
    REQUIRE(k < 7);
    ++counts[k];
  }
  for (int c : counts) CHECK(std::abs(c - 10000) < 500);  // ~5 sigma (sigma ≈ 93)
}

TEST_CASE("normal numbers have mean 0 and variance 1") {
  Random r(3, RandomStage::test, 2);
  const int n = 200000;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    const double x = r.normal();
    REQUIRE(std::isfinite(x));
    sum += x;
    sum2 += x * x;
  }
  CHECK(std::fabs(sum / n) < 0.012);
  CHECK(std::fabs(sum2 / n - 1.0) < 0.02);
}

TEST_CASE("digests see every bit and nothing else") {
  CHECK(Digest().add(1.0).hex() == Digest().add(1.0).hex());
  CHECK(Digest().add(1.0).hex() != Digest().add(std::nextafter(1.0, 2.0)).hex());
  CHECK(Digest().add(0.0).hex() != Digest().add(-0.0).hex());
  CHECK(Digest().add("ab").add("c").hex() != Digest().add("a").add("bc").hex());
  CHECK(Digest().add(std::vector<double>{1, 2}).hex() != Digest().add(std::vector<double>{2, 1}).hex());
  CHECK(Digest().hex().size() == 16);
}

TEST_CASE("parallel_for visits each index once, for any thread count") {
  for (int threads : {1, 2, 3, 8}) {
    std::vector<int> hits(1000, 0);
    parallel_for(1000, threads, [&](int i) { hits[i] += 1; });
    CHECK(std::set<int>(hits.begin(), hits.end()) == std::set<int>{1});
  }
  parallel_for(0, 4, [](int) { FAIL("no item expected"); });
}

TEST_CASE("parallel_for_ranges covers [0, count) once, in consecutive ranges of at most the block") {
  for (int threads : {1, 3})
    for (int count : {0, 1, 7, 4096, 10001}) {
      CAPTURE(threads);
      CAPTURE(count);
      std::vector<int> seen(count, 0), range_of(count, -1);
      parallel_for_ranges(count, 1000, threads, [&](int begin, int end) {
        CHECK(begin % 1000 == 0);
        CHECK(end - begin <= 1000);
        CHECK(end == std::min(count, begin + 1000));
        for (int i = begin; i < end; ++i) ++seen[i], range_of[i] = begin;
      });
      for (int i = 0; i < count; ++i) {
        CHECK(seen[i] == 1);
        CHECK(range_of[i] == i / 1000 * 1000);
      }
    }
}

TEST_CASE("parallel_for inside a loop body, and from two threads at once, still visits each index once") {
  // The worker pool serves one loop at a time; a loop that finds it busy runs on threads of its own.
  std::vector<std::vector<int>> hits(8, std::vector<int>(300, 0));
  parallel_for(8, 3, [&](int outer) { parallel_for(300, 2, [&](int i) { hits[outer][i] += 1; }); });
  for (const std::vector<int>& h : hits) CHECK(std::set<int>(h.begin(), h.end()) == std::set<int>{1});
  std::vector<int> a(5000, 0), b(5000, 0);
  std::thread other([&] {
    for (int k = 0; k < 20; ++k) parallel_for(250, 3, [&](int i) { b[250 * k + i] += 1; });
  });
  for (int k = 0; k < 20; ++k) parallel_for(250, 3, [&](int i) { a[250 * k + i] += 1; });
  other.join();
  CHECK(std::set<int>(a.begin(), a.end()) == std::set<int>{1});
  CHECK(std::set<int>(b.begin(), b.end()) == std::set<int>{1});
}

TEST_CASE("parallel_for's threads are kept from loop to loop") {
  // Thread-local scratch (make_fibre's stations, the guide cost's buffers) survives between loops
  // only if the same threads serve them: two loops in a row see no more distinct threads than the
  // larger of them needs.
  std::mutex mutex;
  std::set<std::thread::id> seen;
  for (int loop = 0; loop < 5; ++loop)
    parallel_for(64, 3, [&](int) {
      std::this_thread::sleep_for(std::chrono::microseconds(200));
      std::lock_guard<std::mutex> lock(mutex);
      seen.insert(std::this_thread::get_id());
    });
  CHECK(seen.size() <= 3);
  CHECK(seen.size() >= 2);
}

TEST_CASE("parallel_for reports the lowest failing index whatever the thread count") {
  for (int threads : {1, 2, 4}) {
    try {
      parallel_for(500, threads, [](int i) {
        if (i % 97 == 13) throw std::runtime_error(std::to_string(i));
      });
      FAIL("expected an exception");
    } catch (const std::runtime_error& e) {
      CHECK(std::string(e.what()) == "13");
    }
  }
}
