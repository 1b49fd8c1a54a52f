#pragma once
// Shared by the studio benchmark's modes.
#include <vector>

/// The q-quantile (0..1) of `v`, nearest rank; 0 for none.
double percentile(std::vector<double> v, double q);

/// `--converge`: time from an edit to a picture within 5 % of the truth, raw and denoised.
int convergence(int runs, int truthPasses);
