#pragma once
// How a boundary condition varies in time: its value is the given one times f(t).
//   constant: f = 1;  linear: f = start + rate t;  sine / cosine: f = sin or cos(2 pi freq t + phase);
//   table: f from (t, f) rows of a file, linear between rows, held at the end values outside.
#include <string>
#include <vector>

namespace vdec {

struct TimeFunction {
  enum class Kind { Constant, Linear, Sine, Cosine, Table } kind = Kind::Constant;
  double start = 1.0, rate = 0.0;         // linear
  double frequency = 0.0, phase = 0.0;    // sine, cosine (Hz, radians)
  std::vector<double> t, f;               // table, t increasing
  std::string name;                       // for messages: the file of a table

  double operator()(double time) const;
};

}  // namespace vdec
