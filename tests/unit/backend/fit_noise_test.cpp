// core/backend/fit_noise: the run's median SRP fit RMS and the rough-fit gate.
#include "backend/fit_noise.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

namespace storey::backend {
namespace {

double lowerMedian(std::vector<double> v) {
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>((v.size() - 1) / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

/// Fit RMS values of a run: plane noise around `noise` [m] (a few per cent
/// spread), one SRP in eight a band of surfaces at 1.6-2.5 times the noise.
std::vector<double> runRms(double noise, int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> spread(1.0, 0.05);
  std::uniform_real_distribution<double> band(1.6, 2.5);
  std::vector<double> rms;
  for (int i = 0; i < count; ++i) rms.push_back(noise * (i % 8 == 5 ? band(rng) : spread(rng)));
  return rms;
}

std::vector<bool> decisions(const std::vector<double>& rms, double max_ratio) {
  FitNoise noise(max_ratio, 20);
  std::vector<bool> rough;
  for (double r : rms) {
    rough.push_back(noise.rough(r));
    noise.add(r);
  }
  return rough;
}

TEST(FitNoise, MedianIsTheLowerMiddleOfAllAdded) {
  FitNoise noise(1.3, 20);
  EXPECT_EQ(noise.median(), 0.0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.001, 0.05);
  std::vector<double> added;
  for (int i = 0; i < 501; ++i) {
    added.push_back(i % 10 == 0 ? 0.02 : u(rng));  // ties too
    noise.add(added.back());
    ASSERT_EQ(noise.median(), lowerMedian(added)) << "after " << added.size();
  }
  EXPECT_EQ(noise.samples(), 501);
}

TEST(FitNoise, GateWaitsForEnoughSrpsAndCanBeSwitchedOff) {
  FitNoise noise(1.3, 20);
  for (int i = 0; i < 19; ++i) noise.add(0.01);
  EXPECT_FALSE(noise.rough(0.05));  // 19 SRPs: no scale yet
  noise.add(0.01);
  EXPECT_TRUE(noise.rough(0.0131));
  EXPECT_FALSE(noise.rough(0.013));  // not above 1.3 x the median
  FitNoise off(0.0, 20);
  for (int i = 0; i < 100; ++i) off.add(0.01);
  EXPECT_FALSE(off.rough(1.0));
}

TEST(FitNoise, RejectsTheBandsAndKeepsThePlanes) {
  const std::vector<double> rms = runRms(0.012, 400, 3);
  const std::vector<bool> rough = decisions(rms, 1.3);
  int bands = 0, bands_rejected = 0, planes_rejected = 0;
  for (std::size_t i = 0; i < rms.size(); ++i) {
    if (i < 20) {
      EXPECT_FALSE(rough[i]);
    } else if (i % 8 == 5) {
      ++bands;
      bands_rejected += rough[i];
    } else {
      planes_rejected += rough[i];
    }
  }
  EXPECT_EQ(bands, 48);
  EXPECT_EQ(bands_rejected, bands);  // every band after the first 20 SRPs
  EXPECT_EQ(planes_rejected, 0);
}

// The gate's scale is the run's own noise: a sensor twice (or half) as noisy
// with the same surfaces gets the same decisions.
TEST(FitNoise, SameDecisionsForANoisierOrQuieterSensor) {
  for (unsigned seed : {1u, 2u, 3u}) {
    const std::vector<double> rms = runRms(0.012, 300, seed);
    std::vector<double> twice, half;
    for (double r : rms) {
      twice.push_back(2.0 * r);
      half.push_back(0.5 * r);
    }
    const std::vector<bool> base = decisions(rms, 1.3);
    EXPECT_GT(std::count(base.begin(), base.end(), true), 30);
    EXPECT_EQ(decisions(twice, 1.3), base);
    EXPECT_EQ(decisions(half, 1.3), base);
    // A fixed threshold (what a gate in metres would be) does not keep them.
    std::vector<bool> fixed;
    for (double r : twice) fixed.push_back(r > 1.3 * 0.012);
    EXPECT_NE(fixed, base);
  }
}

}  // namespace
}  // namespace storey::backend
