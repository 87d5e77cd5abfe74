// The round-off probe (issue 34): a test-only knob that makes the suite's runs feel what another
// processor does to them. Results differ between x86-64 processors in the last bits (glibc's libm
// and OpenBLAS pick code paths per processor); a test that holds only for one rounding (two runs
// required to take the same adaptive steps, the same cutbacks or active counts) passes on the
// machine that wrote it and fails on another. With the environment variable
// IGA_ROUNDOFF_PROBE=<seed> (a non-negative integer) every Newton correction and arc-length
// tangent solution of NonlinearSolver is multiplied, component by component, by
// (1 + 1e-10 xi_i), xi_i uniform in [-1, 1] drawn from a generator seeded by <seed> and the bits
// of the correction itself. Like the rounding of another processor, the probe is a fixed
// function of what it is given: a computation repeated (a restarted run replaying its steps, one
// model built two ways) is perturbed the same way, two different computations that a test
// compares (a rope over a sphere's equator and over its pole) differently. That is round-off
// made a million times larger: it moves the decisions that round-off can move (a point active or
// not at a threshold, a Newton sequence at the edge of its iteration limit), and no result beyond
// what a test's tolerance should allow. Such a decision flips only now and then (the
// perturbation alone fails today's sphere-pole capstan test for 2 seeds of 20), so the probe also
// makes the decision that matters most for such tests itself: it refuses a converged step, with
// the probability 1/8, drawn from the step's state (its times and residual norms), as if it had
// not converged (NewtonOutcome::probe_refused; never a step of the minimum size), and the step
// is cut back as any failed step. A test that requires two runs to take the same steps then
// fails nearly always. Unset (the default), nothing changes.
// scripts/portability.sh runs the whole suite with it (mode `probe`; CI's libm run).
// Tests of the step control itself (exact step counts, observed Newton orders, step growth,
// checkpoints, a restart's replay) count what the probe changes on purpose: they turn it off for
// their scope with a RoundoffProbeOff guard (docs/portability.md lists them).
//
// Notation: du the correction (or tangent solution), xi_i the i-th draw, kRoundoffProbeSize the
// relative size 1e-10, kRoundoffProbeRefusal the probability of a refusal.
#pragma once

#include <vector>

#include <Eigen/Core>

namespace iga {

/// The relative size of the probe's perturbation.
inline constexpr double kRoundoffProbeSize = 1e-10;
/// The probability that the probe refuses a converged step.
inline constexpr double kRoundoffProbeRefusal = 0.125;

/// True when IGA_ROUNDOFF_PROBE is set (read once per process) and no RoundoffProbeOff guard
/// lives. Throws std::invalid_argument naming the variable and its value when it is set but not a
/// non-negative integer.
bool roundoff_probe_enabled();

/// Tests only: the probe is off while an object of this type lives, in every thread of the
/// process (a process-wide count of live guards; guards nest). For tests that count what the probe
/// changes on purpose: a step control's exact steps, cutbacks, Newton orders, a restart's replay.
/// Usage: `const iga::RoundoffProbeOff probe_off;  // why: ...` at the top of the test.
class RoundoffProbeOff {
 public:
  RoundoffProbeOff();
  ~RoundoffProbeOff();
  RoundoffProbeOff(const RoundoffProbeOff&) = delete;
  RoundoffProbeOff& operator=(const RoundoffProbeOff&) = delete;
};

/// du_i <- du_i (1 + 1e-10 xi_i) when the probe is on (xi from the seed and du's bits); nothing
/// otherwise.
void roundoff_probe_perturb(Eigen::VectorXd& du);

/// True (with the probability kRoundoffProbeRefusal, drawn from the seed and the bits of
/// `state`, the step's numbers) when the probe is on and refuses the converged step; always
/// false otherwise.
bool roundoff_probe_refuses(const std::vector<double>& state);

}  // namespace iga
