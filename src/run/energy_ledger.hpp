#pragma once
// The run's energy account, one ledger with named terms. Stages report their step's share in
// the step totals; the cycle closes each step into the ledger in one place, and the energy
// monitor and the reversing-motion stop read it. Everything here is run state: a restart
// carries it as it is.
#include <algorithm>

namespace vdec {

struct EnergyReport {
  double initial = 0.0;            // kinetic energy at the start
  double externalWork = 0.0;       // by gravity, applied loads and driven blocks, to the time of the
                                   // last step's forces (the last step's work counts half)
  double kinetic = 0.0;            // at the end
  double strain = 0.0;             // at the end
  double slipDissipation = 0.0;    // by all contacts, existing and deleted
  double jointRelease = 0.0;       // elastic energy joints gave up without work (breakage, length)
  double plasticDissipation = 0.0; // by Mohr-Coulomb zones
  double removed = 0.0;            // taken out without work between phases (resets, excavation)
  double staticSolve = 0.0;        // elastic energy set up by phases' direct solves, supplied without work
  double thermalStress = 0.0;      // elastic energy the thermal stress set up (1.4-17), supplied without work
  double dampingDissipation = 0.0; // by mass damping
  double boundaryDissipation = 0.0; // by viscous boundaries
  double largestExcess = 0.0;      // max over the run of (kinetic + strain - supplied) / largest supplied
};

class EnergyLedger {
 public:
  // The energy the model holds at the start, and the scale below which a balance is round-off.
  void open(double initial, double floor) {
    terms_.initial = supplied_ = initial;
    floor_ = floor;
  }
  // The step's dissipation and release, as its stages measured them.
  void addDissipation(double slip, double jointRelease, double plastic) {
    terms_.slipDissipation += slip;
    terms_.jointRelease += jointRelease;
    terms_.plasticDissipation += plastic;
  }
  // Kinetic energy is time-centred, so half of a step's external work belongs before the
  // comparison with the mechanical energy and half after it: supplyHalf, then measure, then
  // closeStep.
  void setMechanical(double kinetic, double strain) {
    terms_.kinetic = kinetic;
    terms_.strain = strain;
  }
  void supplyHalf(double work) { supplied_ += 0.5 * work; }
  // Elastic energy a phase's direct solve set up (its loads' work is not formed).
  void supplyByDirectSolve(double energy) {
    supplied_ += energy;
    terms_.staticSolve += energy;
  }
  // Elastic energy the temperature change put into the zones (its loads are not forces).
  void supplyByThermalStress(double energy) {
    supplied_ += energy;
    terms_.thermalStress += energy;
  }
  // Energy taken out of the model without work (velocities reset between phases).
  void withdraw(double energy) {
    supplied_ -= energy;
    terms_.removed += energy;
  }
  // kinetic + strain - supplied, recorded against the largest energy supplied so far, which it
  // also updates: the energy supplied can return to zero (a bouncing block back at its start),
  // where the discrete energies' O((w dt)^2) errors do not.
  double measureExcess() {
    largestSupplied_ = std::max({largestSupplied_, supplied_, floor_});
    const double excess = mechanical() - supplied_;
    terms_.largestExcess = std::max(terms_.largestExcess, excess / largestSupplied_);
    return excess;
  }
  void closeStep(double externalWork, double damping, double boundary) {
    supplyHalf(externalWork);
    terms_.externalWork += externalWork;
    lastExternalWork_ = externalWork;
    terms_.dampingDissipation += damping;
    terms_.boundaryDissipation += boundary;
  }

  double mechanical() const { return terms_.kinetic + terms_.strain; }
  // The account's error as it stands after the last step: the energy held (kinetic + strain) and
  // spent (dissipated by damping, dashpots, slip and plasticity, released by joints) less the
  // energy supplied, over the largest energy supplied so far; round-off for a closed account.
  double balanceError() const {
    const double spent = terms_.dampingDissipation + terms_.boundaryDissipation + terms_.slipDissipation +
                         terms_.jointRelease + terms_.plasticDissipation;
    return largestSupplied_ > 0.0 ? (mechanical() + spent - supplied_) / largestSupplied_ : 0.0;
  }
  double kinetic() const { return terms_.kinetic; }
  double strain() const { return terms_.strain; }
  double supplied() const { return supplied_; }
  double largestSupplied() const { return largestSupplied_; }
  // The terms as results.json reports them: strain and kinetic energy are those of the
  // positions the last step started from, so the work of that step, done over the motion it
  // produced, comes after them.
  EnergyReport report() const {
    EnergyReport r = terms_;
    r.externalWork -= lastExternalWork_;
    return r;
  }

 private:
  EnergyReport terms_;
  double supplied_ = 0.0;          // initial energy + external work so far
  double largestSupplied_ = 0.0;
  double floor_ = 0.0;
  double lastExternalWork_ = 0.0;
};

}  // namespace vdec
