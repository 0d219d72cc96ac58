// The tissue material as one value: a choice of law (a std::variant of small value types) plus
// the name it was built from, so every output can say which material it used.
//
// Laws, each in its own file with the members point_response.hpp lists:
//  * PolynomialTissue: decoupled polynomial (N = 2) isochoric energy wrapped in a Prony series
//    plus U(J) = K/2 (J - 1)² (polynomial_tissue.hpp).
//  * CorotationalLinear: paper 000's co-rotational linear elastic tissue (corotational.hpp).
// A new law is a new file and an entry in MaterialLaw; Material and the element kernel reach it
// through std::visit only.
//
// Every law is a pure function of F, the internal state at the start of the step and the time
// step; nothing is mutated. Consistent tangents are exact derivatives of the stepped stress,
// computed with Dual numbers (tensor.hpp).
#pragma once

#include <string>
#include <variant>
#include <vector>

#include "physics/material/corotational.hpp"
#include "physics/material/polynomial_tissue.hpp"
#include "physics/material/tensor.hpp"
#include "physics/material/viscoelastic.hpp"

#include "case/specs/material_spec.hpp"

namespace needlefem::material {

using MaterialLaw = std::variant<PolynomialTissue, CorotationalLinear>;
static_assert(PointwiseLaw<PolynomialTissue> && PointwiseLaw<CorotationalLinear>);

struct MaterialPointResult {
  Mat3d first_pk;   // P = F S
  Mat3d second_pk;  // S
  ViscousState state;  // internal variables at the end of the step
};

class Material {
 public:
  Material(std::string name, MaterialLaw law) : name_(std::move(name)), law_(std::move(law)) {}

  const std::string& name() const { return name_; }
  const MaterialLaw& law() const { return law_; }

  ViscousState initial_state() const;
  // Prony terms of the law's internal variables (empty for elastic laws).
  const std::vector<PronyTerm>& prony() const;
  // Stress at deformation gradient F after a step of length dt (s) from internal state `old`.
  // dt = 0 gives the instantaneous response, dt = +inf the fully relaxed one.
  MaterialPointResult update(const Mat3d& F, const ViscousState& old, double dt) const;
  // Split laws only: the isochoric S_iso of update() (the volumetric part left out), for
  // drivers that impose J = 1 and find the pressure from a traction condition instead.
  Mat3d isochoric_second_pk(const Mat3d& F, const ViscousState& old, double dt) const;
  // update()'s internal variables alone.
  ViscousState advance(const Mat3d& F, const ViscousState& old, double dt) const;
  // Consistent tangent A_iJkL = ∂P_iJ/∂F_kL of update()'s first Piola-Kirchhoff stress.
  Tensor4 tangent(const Mat3d& F, const ViscousState& old, double dt) const;
  // Consistent tangent ∂S_IJ/∂E_KL of update()'s second Piola-Kirchhoff stress (minor
  // symmetric in KL), for total-Lagrangian elements written with S and E.
  Tensor4 tangent_green_strain(const Mat3d& F, const ViscousState& old, double dt) const;
  // Instantaneous strain-energy density W(F) (Pa); update(F, ·, 0).first_pk = ∂W/∂F from rest.
  double instantaneous_energy(const Mat3d& F) const;

  // True for laws with an isochoric/volumetric split, whose material-point driver imposes
  // J = 1 exactly (the volumetric part then carries only the constraint pressure).
  bool incompressible() const {
    return std::visit([](const auto& law) { return law.kVolumetricSplit; }, law_);
  }
  double instantaneous_shear_modulus() const;
  double long_term_shear_modulus() const;
  // One line naming the material and all its constants, for logs and output headers.
  std::string description() const;

 private:
  // S after a step, on double or Dual (defined in material.cpp, its only user).
  template <class T>
  Mat3<T> stepped_second_pk(const Mat3<T>& F, const ViscousState& old, double dt) const;

  std::string name_;
  MaterialLaw law_;
};

// Names accepted by material_preset(): "miller-brain", "miller-brain-c10-c20".
const std::vector<std::string>& material_preset_names();
// A preset with every other [material] key at its schema default.
Material material_preset(const std::string& name);
// The material of a case's [material] table (parse_material_spec, which checks it).
Material material_from_spec(const MaterialSpec& spec);

}  // namespace needlefem::material
