// vdec_cy_reference: independent 50-digit reference for the continuously-yielding (CY) joint
// (Cundall & Hart 1984; Lemos 1987; NUREG/CR-5429 eqs 1.4-137 to 1.4-145) in direct shear at
// constant normal stress. It shares no code with the vdec solver; verification/analytic/joints.py
// runs it.
//
// Usage:
//   vdec_cy_reference --ks KS --sn SN --phi PHI --phi0 PHI0 --roughness R
//                     [--turning-points a,b,c] < samples
//   (--name=value is accepted too). ks in Pa/m, sn in Pa (compression positive, held constant),
//   phi (basic friction) and phi0 (initial phi_eff) in degrees, 0 < phi <= phi0 < 90, R in m.
//   Turning points: the shear displacements us (m) at which the direction reverses, in order;
//   the path is 0 -> a -> b -> c -> ... and then onwards in the last direction.
// stdin: the requested us (m), one per line, in time order along the path, starting from
//   us = 0; blank lines are skipped. Between consecutive samples p -> q the path passes through
//   the next turning point when q lies beyond it or q lies behind p.
// stdout, one line per sample, 20 significant digits:
//   us tau phi_eff_deg us_p opening err_tau err_opening err_phi_eff_deg err_us_p
//   tau in Pa, signed along +us; us_p the accumulated plastic shear path (m); opening the
//   dilatant normal opening (m, positive = opening). The err_* columns are the absolute
//   differences between the printed run and a second, less accurate one (see Method): a bound,
//   with a wide margin, on the printed values' own error.
// Exit status: 0, or 2 on a bad option or input (stderr names the option or the stdin line).
//
// Model, along a monotonic segment of direction d = +-1 and path length s:
//   tau_m = d sn tan(phi_eff),  F = (1 - tau/tau_m) / (1 - r)
//   dtau/ds = d ks F,  dphi_eff/ds = -(phi_eff - phi)(1 - F)/R,  dus_p/ds = 1 - F,
//   dopening/ds = (1 - F) tan(max(0, atan(|tau|/sn) - phi))  (dilation with the plastic shear),
// with r = 0 initially and r = min(tau/tau_m, 0.75) (the new direction's tau_m) at a reversal.
//
// Method: Gragg-Bulirsch-Stoer extrapolation of the modified midpoint rule at a fixed high order
// (odeint's extrapolation_stepper) under odeint's standard step-size controller, because the
// tolerance is far below what low orders reach cheaply: over one elastic length sn/ks at 1e-42,
// Runge-Kutta-Fehlberg 7(8) took 42941 steps (3 s), order 24 extrapolation 16 steps (0.01 s);
// odeint's order-adaptive bulirsch_stoer, capped at order 17, was 15 times slower than order 24
// on a 500-sample path. The printed values come from order 24 at tolerance 1e-42; the error
// estimate from a second run at order 18 and tolerance 1e-32, whose different order keeps its
// steps (and so its errors) apart from the first run's even where sample points cut the steps.
// The kink of the opening's right-hand side at |tau| = sn tan(phi) is located by root finding
// and the integration restarted there, each side with its own smooth branch, so that the
// method keeps its order.

#include <array>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <map>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <boost/math/constants/constants.hpp>
#include <boost/multiprecision/cpp_dec_float.hpp>
#include <boost/numeric/odeint/integrate/integrate_adaptive.hpp>
#include <boost/numeric/odeint/stepper/controlled_runge_kutta.hpp>
#include <boost/numeric/odeint/stepper/extrapolation_stepper.hpp>

using Real = boost::multiprecision::cpp_dec_float_50;

// Boost 1.74's odeint follows value_type chains to find a state's scalar, and a multiprecision
// number names itself as its value_type, which never ends; this stops the chain at Real.
template <>
struct boost::numeric::odeint::detail::extract_value_type<Real, void> {
  using type = Real;
};

namespace {

namespace odeint = boost::numeric::odeint;

// Dimensionless state, lengths in units of L = sn/ks and stresses in units of sn, so that one
// relative/absolute tolerance fits every component. tan(phi_eff) is carried as a state of its
// own (d tan/ds = (1 + tan^2) dphi/ds) because a 50-digit tan costs far more than the rest of
// the right-hand side together.
enum { TAU, PHI, TAN_PHI, US_P, OPEN, N_STATE };
using State = std::array<Real, N_STATE>;
using ErrorChecker = odeint::default_error_checker<Real, odeint::array_algebra, odeint::default_operations>;
template <unsigned short Order>
using Stepper = odeint::controlled_runge_kutta<odeint::extrapolation_stepper<Order, State, Real>>;

struct Input {
  Real ks, sn, phi_deg, phi0_deg, roughness;
  std::vector<Real> turning_points;
  std::vector<Real> samples;
  std::vector<std::size_t> sample_lines;  // for messages
};

[[noreturn]] void bad_input(const std::string& message) {
  std::cerr << "vdec_cy_reference: " << message << "\n";
  std::exit(2);
}

std::optional<Real> parse_number(const std::string& text) {
  static const std::regex number(R"(\s*[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?\s*)");
  if (!std::regex_match(text, number)) return std::nullopt;
  std::size_t first = text.find_first_not_of(" \t\r");
  std::size_t last = text.find_last_not_of(" \t\r");
  return Real(text.substr(first, last - first + 1));
}

struct Rhs {
  int d;
  Real inv_one_minus_r;
  bool dilating;
  Real l_over_r, phi_b, tan_phi_b;

  void operator()(const State& y, State& dy, const Real& /*s*/) const {
    Real tau_m = d * y[TAN_PHI];
    Real f = (1 - y[TAU] / tau_m) * inv_one_minus_r;
    dy[TAU] = d * f;
    dy[PHI] = -(y[PHI] - phi_b) * (1 - f) * l_over_r;
    dy[TAN_PHI] = (1 + y[TAN_PHI] * y[TAN_PHI]) * dy[PHI];
    dy[US_P] = 1 - f;
    if (dilating) {
      // tan(atan(|tau|/sn) - phi) without transcendental functions.
      Real a = abs(y[TAU]);
      dy[OPEN] = (1 - f) * (a - tan_phi_b) / (1 + a * tan_phi_b);
    } else {
      dy[OPEN] = 0;
    }
  }
};

template <unsigned short Order>
class Path {
 public:
  Path(const Input& in, const Real& tol) : tol_(tol), l_(in.sn / in.ks) {
    const Real deg = boost::math::constants::pi<Real>() / 180;
    rhs_.d = 0;
    rhs_.inv_one_minus_r = 1;
    rhs_.dilating = false;
    rhs_.l_over_r = l_ / in.roughness;
    rhs_.phi_b = in.phi_deg * deg;
    rhs_.tan_phi_b = tan(rhs_.phi_b);
    y_[TAU] = 0;
    y_[PHI] = in.phi0_deg * deg;
    y_[TAN_PHI] = tan(y_[PHI]);
    y_[US_P] = 0;
    y_[OPEN] = 0;
    turning_points_ = in.turning_points;
  }

  const State& go_to(const Real& us, std::size_t line) {
    for (;;) {
      if (rhs_.d == 0) {
        if (next_tp_ < turning_points_.size()) {
          rhs_.d = turning_points_[next_tp_] > 0 ? 1 : -1;
        } else if (us != pos_) {
          rhs_.d = us > pos_ ? 1 : -1;
        } else {
          return y_;
        }
      }
      bool has_tp = next_tp_ < turning_points_.size();
      if (has_tp && (rhs_.d * (us - turning_points_[next_tp_]) > 0 || rhs_.d * (us - pos_) < 0)) {
        advance(turning_points_[next_tp_]);
        reverse();
        ++next_tp_;
        continue;
      }
      if (rhs_.d * (us - pos_) < 0) {
        bad_input("stdin line " + std::to_string(line) +
                  ": the sample lies behind the previous one and no turning point is left");
      }
      advance(us);
      return y_;
    }
  }

 private:
  Real g(const State& y) const { return abs(y[TAU]) - rhs_.tan_phi_b; }

  void reverse() {
    rhs_.d = -rhs_.d;
    Real r = y_[TAU] / (rhs_.d * y_[TAN_PHI]);
    if (r > Real(0.75)) r = Real(0.75);
    rhs_.inv_one_minus_r = 1 / (1 - r);
    segment_start_ = pos_;
    s_ = 0;
  }

  // Integrates along the current direction to the shear displacement us.
  void advance(const Real& us) {
    const Real s_end = rhs_.d * (us - segment_start_) / l_;
    while (s_ < s_end) {
      Real h = h_ < s_end - s_ ? h_ : s_end - s_;
      const bool reaches_end = h == s_end - s_;
      const State y_before = y_;
      const Real s_before = s_;
      if (stepper_.try_step(rhs_, y_, s_, h) != odeint::success) {
        h_ = h;
        continue;
      }
      if (reaches_end) s_ = s_end;
      if (h > 0) h_ = h;
      const Real g_after = g(y_);
      if ((g_after > 0) != rhs_.dilating && g_after != 0) {
        locate_kink(y_before, s_before, g_after);
        rhs_.dilating = !rhs_.dilating;
      }
    }
    pos_ = us;
  }

  State state_at(const State& y0, const Real& s0, const Real& s1) const {
    State y = y0;
    if (s1 > s0) {
      Stepper<Order> stepper(ErrorChecker(tol_, tol_));
      odeint::integrate_adaptive(stepper, rhs_, y, s0, s1, Real(s1 - s0));
    }
    return y;
  }

  // Illinois regula falsi for g = 0 between (s_before, y_before) and the current (s_, y_);
  // leaves the state at the root.
  void locate_kink(const State& y_before, const Real& s_before, const Real& g_after) {
    Real sa = s_before, ga = g(y_before);
    Real sb = s_, gb = g_after;
    Real sc = sb;
    State yc = y_;
    const Real tiny_s = Real("1e-44") * (1 + abs(sb));
    for (int iter = 0; iter < 200 && ga != 0; ++iter) {
      sc = sb - gb * (sb - sa) / (gb - ga);
      yc = state_at(y_before, s_before, sc);
      const Real gc = g(yc);
      if (gc == 0) break;
      if ((gc > 0) != (gb > 0)) {
        sa = sb;
        ga = gb;
      } else {
        ga /= 2;
      }
      sb = sc;
      gb = gc;
      if (abs(sb - sa) < tiny_s) break;
    }
    if (ga == 0) {
      sc = sa;
      yc = state_at(y_before, s_before, sc);
    }
    s_ = sc;
    y_ = yc;
  }

  Real tol_;
  Real l_;
  Rhs rhs_;
  State y_;
  std::vector<Real> turning_points_;
  std::size_t next_tp_ = 0;
  Real pos_ = 0;
  Real segment_start_ = 0;
  Real s_ = 0;
  Real h_ = Real(0.01);
  Stepper<Order> stepper_{ErrorChecker(tol_, tol_)};
};

template <unsigned short Order>
std::vector<State> run(const Input& in, const Real& tol) {
  Path<Order> path(in, tol);
  std::vector<State> out;
  out.reserve(in.samples.size());
  for (std::size_t i = 0; i < in.samples.size(); ++i) {
    out.push_back(path.go_to(in.samples[i], in.sample_lines[i]));
  }
  return out;
}

const char* const kUsage =
    "usage: vdec_cy_reference --ks KS --sn SN --phi PHI_DEG --phi0 PHI0_DEG --roughness R\n"
    "                         [--turning-points a,b,c] < samples (one us per line)\n";

Input parse_arguments(int argc, char** argv) {
  std::map<std::string, std::string> values;
  const std::vector<std::string> known = {"--ks", "--sn", "--phi", "--phi0", "--roughness",
                                          "--turning-points"};
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      std::cout << kUsage;
      std::exit(0);
    }
    std::string name = arg, value;
    bool has_value = false;
    if (auto eq = arg.find('='); arg.rfind("--", 0) == 0 && eq != std::string::npos) {
      name = arg.substr(0, eq);
      value = arg.substr(eq + 1);
      has_value = true;
    }
    bool is_known = false;
    for (const auto& k : known) is_known = is_known || k == name;
    if (!is_known) bad_input("unknown option " + name + "\n" + kUsage);
    if (!has_value) {
      if (i + 1 >= argc) bad_input("option " + name + " needs a value");
      value = argv[++i];
    }
    if (values.count(name)) bad_input("option " + name + " given twice");
    values[name] = value;
  }

  auto number = [&](const std::string& name) {
    auto it = values.find(name);
    if (it == values.end()) bad_input("missing required option " + name + "\n" + kUsage);
    auto x = parse_number(it->second);
    if (!x) bad_input("option " + name + ": '" + it->second + "' is not a number");
    return *x;
  };
  Input in;
  in.ks = number("--ks");
  in.sn = number("--sn");
  in.phi_deg = number("--phi");
  in.phi0_deg = number("--phi0");
  in.roughness = number("--roughness");
  if (!(in.ks > 0)) bad_input("option --ks must be positive (got " + values["--ks"] + ")");
  if (!(in.sn > 0)) {
    bad_input("option --sn must be positive, compression (got " + values["--sn"] + ")");
  }
  if (!(in.phi_deg > 0 && in.phi_deg < 90)) {
    bad_input("option --phi must lie in (0, 90) degrees (got " + values["--phi"] + ")");
  }
  if (!(in.phi0_deg >= in.phi_deg && in.phi0_deg < 90)) {
    bad_input("option --phi0 must lie in [phi, 90) degrees (got " + values["--phi0"] + ")");
  }
  if (!(in.roughness > 0)) {
    bad_input("option --roughness must be positive (got " + values["--roughness"] + ")");
  }

  if (auto it = values.find("--turning-points"); it != values.end() && !it->second.empty()) {
    std::stringstream list(it->second);
    std::string item;
    Real previous = 0;
    int previous_direction = 0;
    while (std::getline(list, item, ',')) {
      auto x = parse_number(item);
      if (!x) bad_input("option --turning-points: '" + item + "' is not a number");
      const int direction = *x > previous ? 1 : (*x < previous ? -1 : 0);
      if (direction == 0 || direction == previous_direction) {
        bad_input("option --turning-points: '" + item +
                  "' does not reverse the direction of the path before it");
      }
      in.turning_points.push_back(*x);
      previous = *x;
      previous_direction = direction;
    }
  }

  std::string line;
  for (std::size_t n = 1; std::getline(std::cin, line); ++n) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    auto x = parse_number(line);
    if (!x) bad_input("stdin line " + std::to_string(n) + ": '" + line + "' is not a number");
    in.samples.push_back(*x);
    in.sample_lines.push_back(n);
  }
  return in;
}

}  // namespace

int main(int argc, char** argv) {
  const Input in = parse_arguments(argc, argv);
  const std::vector<State> fine = run<24>(in, Real("1e-42"));
  const std::vector<State> coarse = run<18>(in, Real("1e-32"));

  const Real l = in.sn / in.ks;
  const Real to_deg = 180 / boost::math::constants::pi<Real>();
  std::cout << std::scientific << std::setprecision(19);
  for (std::size_t i = 0; i < in.samples.size(); ++i) {
    const State& y = fine[i];
    const State& e = coarse[i];
    std::cout << in.samples[i] << ' ' << y[TAU] * in.sn << ' ' << y[PHI] * to_deg << ' '
              << y[US_P] * l << ' ' << y[OPEN] * l << ' ' << abs(y[TAU] - e[TAU]) * in.sn << ' '
              << abs(y[OPEN] - e[OPEN]) * l << ' ' << abs(y[PHI] - e[PHI]) * to_deg << ' '
              << abs(y[US_P] - e[US_P]) * l << '\n';
  }
  return 0;
}
