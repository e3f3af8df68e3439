// Each component's stages and step limit, as sceneComponents gives them to the cycle.
#include <algorithm>
#include <cmath>

#include "boundary/boundary_conditions.hpp"
#include "bem/far_field.hpp"
#include "boundary/free_field.hpp"
#include "boundary/viscous_boundary.hpp"
#include "contact/deformable_outline.hpp"
#include "flow/fracture_flow.hpp"
#include "motion/gridpoint_motion.hpp"
#include "motion/rigid_motion.hpp"
#include "motion/strain_modes.hpp"
#include "run/component.hpp"
#include "structure/beams.hpp"
#include "structure/bolts.hpp"
#include "structure/cables.hpp"
#include "zone/cst.hpp"

namespace vdec {

namespace {

bool anyRigidBlock(const Model& m) {
  for (int b = 0; b < m.blocks.size(); ++b)
    if (!m.blocks.deformable[b]) return true;
  return false;
}

Component contacts(RunContext& run) {
  Component c{"contacts", {}, {}};
  c.stages.push_back({"contact-detection", [&run] {
                        if (run.model.cycle > 0) {
                          run.detection.checkStepReach(run.model, run.dt, run.largestStepDisplacement);
                          run.detection.update(run.model, run.largestStepDisplacement);
                        }
                        run.motionClock += run.largestStepDisplacement;
                      }});
  c.stages.push_back({"contact-forces", [&run] {
                        // As for the zones: before the first step no motion has happened for the
                        // initial velocities, v(-dt/2), to have displaced the joints.
                        const ContactStepTotals t = computeContactForces(
                            run.model, run.model.cycle == 0 ? 0.0 : run.dt, run.motionClock, run.settings.stiffnessDamping);
                        run.checkStiffnessGrowth(t);
                        run.detection.requestRescan(t.passedCorners);
                        run.step.strainEnergy += t.strainEnergy;
                        run.energy.addDissipation(t.slipDissipation, t.jointRelease, 0.0);
                        run.step.dampingDissipation += t.viscousDissipation;
                        run.step.forceScaleSum += t.sumForceMagnitude;
                        run.step.forceCount += t.closedContacts;
                      }});
  return c;
}

// Tractions, dashpots and driven velocities of the boundary conditions in force: a stage for each
// kind there is.
Component boundaries(RunContext& run) {
  Component c{"boundaries", {}, {}};
  const Model& m = run.model;
  const bool gridDashpots = !m.viscousEdges.empty() || !m.freeFields.empty(), rigidDashpots = !m.rigidViscousEdges.empty();
  if (gridDashpots || rigidDashpots)
    c.stepLimit = [&run, gridDashpots, rigidDashpots] {
      return std::min(gridDashpots ? run.settings.zoneFraction * dashpotTimeStep(run.model) : INFINITY,
                      rigidDashpots ? rigidDashpotTimeStep(run.model, run.settings.frac) : INFINITY);
    };
  if (!m.loadedEdges.empty()) c.stages.push_back({"boundary-tractions", [&run] { applyEdgeTractions(run.model); }});
  if (!m.viscousEdges.empty()) c.stages.push_back({"viscous-boundaries", [&run] { applyViscousBoundaries(run.model); }});
  if (rigidDashpots)
    c.stages.push_back({"rigid-viscous-boundaries", [&run] { applyRigidViscousBoundaries(run.model); }});
  if (!m.drivenVelocities.empty())
    c.stages.push_back({"boundary-velocities", [&run] { applyDrivenVelocities(run.model, run.dt); }});
  return c;
}

// The boundary-element far field (1.4.5): its forces on the interface's points (gridpoints, rigid
// blocks' vertices) from their displacements, a force stage; its stiffness in their step.
Component boundaryElements(RunContext& run) {
  Component c{"boundary-elements", {}, [&run] { return boundaryElementTimeStep(run.model, run.settings.frac, run.settings.zoneFraction); }};
  c.stages.push_back({"boundary-element-forces", [&run] { applyBoundaryElementForces(run.model); }});
  return c;
}

// The free-field columns beside the lateral boundaries (1.3.6.3): their loads on the sides are
// forces of the step, and the columns move in the same stage, on their own.
Component freeField(RunContext& run) {
  Component c{"free-field", {}, [&run] { return freeFieldTimeStep(run.model); }};
  c.stages.push_back({"free-field", [&run] {
                        stepFreeFields(run.model, run.dt, run.massDamping, run.settings.stiffnessDamping);
                      }});
  return c;
}

Component rigidMotion(RunContext& run) {
  // 1.3-28 through the joints of the blocks that move; with zones and no free rigid block the
  // zones' step (which includes the joints' stiffness at gridpoints) decides.
  const Model& m = run.model;
  bool anyFree = false;
  for (int b = 0; b < m.blocks.size(); ++b) anyFree = anyFree || m.blocks.movesFreely(b);
  Component c{"rigid-block-motion", {}, {}};
  // A simply-deformable block's strains move even while its rigid motion is driven.
  if (anyFree || m.zones.size() == 0)
    c.stepLimit = [&run] {
      return std::min(rigidBlockTimeStep(run.model, run.settings.frac), strainModeTimeStep(run.model, run.settings.frac));
    };
  else if (m.strainModes.size() > 0)
    c.stepLimit = [&run] { return strainModeTimeStep(run.model, run.settings.frac); };
  // Simply-deformable blocks: their stresses from the strains at the step's start (the step's
  // force stages run before any motion).
  if (m.strainModes.size() > 0)
    c.stages.push_back({"strain-mode-stress", [&run] { run.step.strainEnergy += strainModeStress(run.model); }});
  c.stages.push_back({"rigid-block-motion",
                      [&run] {
                        run.step.merge(integrateRigidBlocks(run.model, run.dt, run.massDamping, run.settings.localDamping));
                      },
                      StepPart::Motion});
  return c;
}

// Zones (forces) and gridpoints (motion) of the deformable blocks; the zone step (1.3-25).
Component deformableBlocks(RunContext& run) {
  Component c{"deformable-blocks", {}, [&run] { return run.settings.zoneFraction * zoneTimeStep(run.model); }};
  // The first step starts from the given configuration and stress: no motion has happened yet
  // for the initial velocities, v(-dt/2), to have strained the zones.
  c.stages.push_back({"zone-forces", [&run] {
                        const ZoneStepTotals t = computeZoneForces(run.model, run.model.cycle == 0 ? 0.0 : run.dt,
                                                                   run.settings.stiffnessDamping);
                        run.step.strainEnergy += t.strainEnergy;
                        run.energy.addDissipation(0.0, 0.0, t.plasticDissipation);
                        run.step.dampingDissipation += t.viscousDissipation;
                      }});
  // Deformable blocks' outlines follow their gridpoints at once, so that the next step's
  // contacts and this step's outputs see the positions just reached.
  std::vector<int> outlined;
  for (int b = 0; run.model.blocks.size() > 1 && b < run.model.blocks.size(); ++b)
    if (run.model.blocks.deformable[b]) outlined.push_back(b);
  c.stages.push_back({"gridpoint-motion",
                      [&run, outlined] {
                        run.step.merge(integrateGridpoints(run.model, run.dt, run.massDamping, run.settings.localDamping));
                        for (const int b : outlined) placeOutlineVertices(run.model, b);
                      },
                      StepPart::Motion});
  return c;
}

// Fluid in the joints (1.2, Fig. 1.2-5): the domain pressures load the blocks with the step's
// forces; after the motion the network follows the contacts and the fluid flows over the step.
Component fractureFlow(RunContext& run) {
  // The steady scheme stores no fluid: the pressures follow the apertures, not the areas, and the
  // fluid is no spring on the blocks.
  Component c{"fracture-flow", {}, {}};
  if (run.model.flow.fluid.scheme != FlowScheme::Steady)
    c.stepLimit = [&run] { return fluidMechanicalTimeStep(run.model, run.settings.frac); };
  c.stages.push_back({"fluid-pressures", [&run] { applyDomainPressures(run.model); }});
  c.stages.push_back({"fluid-flow", [&run] { stepFlow(run.model, run.dt); }, StepPart::Motion});
  return c;
}

// Beams, cables and bolts (1.4.4): the elements', ties' and reinforcements' forces with the step's forces, the nodes' motion with
// the blocks'. The ties' springs and slip enter the energy account as work on nodes and rock.
Component structures(RunContext& run) {
  Component c{"structures", {}, [&run] {
                const double frac = run.settings.frac, zoneFraction = run.settings.zoneFraction;
                return std::min({beamTimeStep(run.model, frac, zoneFraction), cableTimeStep(run.model, frac, zoneFraction),
                                 boltTimeStep(run.model, frac, zoneFraction)});
              }};
  const Structures& st = run.model.structures;
  if (!st.beams.empty()) {
    c.stages.push_back({"beam-forces", [&run] {
                          run.step.strainEnergy += computeBeamForces(run.model, run.model.cycle == 0 ? 0.0 : run.dt).strainEnergy;
                        }});
  }
  if (!st.cables.empty()) {
    c.stages.push_back({"cable-forces", [&run] {
                          const CableStepTotals t = computeCableForces(run.model, run.model.cycle == 0 ? 0.0 : run.dt);
                          run.step.strainEnergy += t.strainEnergy;
                          run.energy.addDissipation(0.0, 0.0, t.plasticWork);
                        }});
  }
  if (!st.bolts.empty()) {
    // The reinforcements' work on the rock is the blocks' external work (as the ties' and the
    // grout's): what they store and dissipate (yield, crushing) stays outside the account.
    c.stages.push_back({"bolt-forces", [&run] {
                          const BoltStepTotals t = computeBoltForces(run.model, run.model.cycle == 0 ? 0.0 : run.dt);
                          run.step.forceScaleSum += t.sumForceMagnitude;
                          run.step.forceCount += t.acting;
                        }});
  }
  if (!st.beams.empty()) {
    c.stages.push_back({"beam-motion",
                        [&run] {
                          run.step.merge(integrateBeamNodes(run.model, run.dt, run.massDamping, run.settings.localDamping));
                        },
                        StepPart::Motion});
  }
  if (!st.cables.empty()) {
    c.stages.push_back({"cable-motion",
                        [&run] {
                          run.step.merge(integrateCableNodes(run.model, run.dt, run.massDamping, run.settings.localDamping));
                        },
                        StepPart::Motion});
  }
  return c;
}

}  // namespace

std::vector<Component> sceneComponents(RunContext& run) {
  const Model& m = run.model;
  std::vector<Component> components;
  if (m.blocks.size() > 1) components.push_back(contacts(run));
  if (anyRigidBlock(m)) components.push_back(rigidMotion(run));
  if (m.zones.size() > 0) components.push_back(deformableBlocks(run));
  if (m.zones.size() > 0 || !m.rigidViscousEdges.empty()) components.push_back(boundaries(run));
  if (!m.freeFields.empty()) components.push_back(freeField(run));
  if (m.boundaryElements.on) components.push_back(boundaryElements(run));
  if (m.flow.on) components.push_back(fractureFlow(run));
  if (m.structures.any()) components.push_back(structures(run));
  return components;
}

}  // namespace vdec
