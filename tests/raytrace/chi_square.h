#pragma once
// The chi-square test of a sampling routine against the density it claims (pbrt-v4's
// bsdfs_test.cpp): draw a million directions, histogram them over 80 x 160 theta/phi
// cells, integrate the pdf over each cell (adaptive Simpson), pool the cells expected
// to hold fewer than 5 samples, and ask how likely the counts are under the pdf.
// A routine whose pdf is off by a few per cent anywhere fails.
#include <functional>
#include <string>

#include <glm/glm.hpp>

namespace chi2 {

struct Result {
  double pValue = 0.0;
  double statistic = 0.0;
  int degreesOfFreedom = 0;
  std::string message;  // what failed, for the test's output
};

// `sample(u)` returns a unit direction (local frame, theta from +z), or false to say
// it drew nothing; `pdf(w)` its solid-angle density.
using SampleFn = std::function<bool(glm::vec2 u, glm::vec3* w)>;
using PdfFn = std::function<double(const glm::vec3& w)>;

Result test(const SampleFn& sample, const PdfFn& pdf, int sampleCount = 1000000, int thetaRes = 80, int phiRes = 160,
            unsigned seed = 1);

// The per-test significance that keeps the whole suite's false-alarm rate at alpha
// (Sidak's correction).
double sidak(double alpha, int tests);

}  // namespace chi2
