#pragma once
// How a boundary condition varies in time: its value is the given one times f(t).
//   constant: f = 1;  linear: f = start + rate t;  sine / cosine: f = sin or cos(2 pi freq t + phase);
//   table: f from (t, f) rows of a file, linear between rows, held at the end values outside;
//   integrated table: f(t) = the integral from 0 to t of that table (an acceleration record
//   applied as the velocity it gives from rest, exact for the piecewise-linear record).
#include <string>
#include <vector>

namespace vdec {

struct TimeFunction {
  enum class Kind { Constant, Linear, Sine, Cosine, Table } kind = Kind::Constant;
  double start = 1.0, rate = 0.0;         // linear
  double frequency = 0.0, phase = 0.0;    // sine, cosine (Hz, radians)
  std::vector<double> t, f;               // table, t increasing
  std::string name;                       // for messages: the file of a table
  bool integrated = false;                // table: its integral from 0
  std::vector<double> antiderivative;     // integrated table: the integral from t[0] to each row
  double atZero = 0.0;                    // integrated table: the antiderivative at t = 0

  // Forms the antiderivative of an integrated table (once its rows are read).
  void integrate();
  double operator()(double time) const;

 private:
  double tableAntiderivative(double time) const;
};

}  // namespace vdec
