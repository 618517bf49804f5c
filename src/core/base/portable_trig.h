#pragma once
// sin, cos and atan2 whose bits are the same on every x86-64 CPU, for the signals a
// step reads from the clock (a pin's oscillation, the wind's gusts). The C
// library's own pick their code when the program loads, by the CPU (glibc has
// separate versions for CPUs with and without FMA), and the two may differ in
// the last bit: the flag's gusts under explicit Euler ran to other bits on an
// emulated CPU without FMA than on this one (docs/testing.md, "Stored
// determinism hashes"). These use only +, -, * and one rounding to an integer,
// in IEEE double with contraction off, so every CPU gives the same bits.
//
// Accuracy: within about 2 ulp of the true value for |x| < 1e6 (the tests hold
// them to the C library's values there), which is all a signal of the clock
// needs. Larger |x| loses accuracy with the argument reduction but stays a
// deterministic function in [-1, 1]; a NaN or an infinity gives a NaN.
namespace neurocloth {

double portable_sin(double x);
double portable_cos(double x);
// The angle of (x, y) in [-pi, pi], as std::atan2 (signed zeros aside): for
// the angles a step computes from positions (a fold's), which must not change
// bits with the CPU either. Within a few ulp of the C library's.
double portable_atan2(double y, double x);

}  // namespace neurocloth
