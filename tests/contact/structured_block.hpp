// Test meshes and drivers of the contact tests: a graded structured block of 10-node tets (each
// grid cell cut into the 6 Kuhn tetrahedra around its main diagonal, edge nodes at edge
// midpoints), boundary faces named x_min .. z_max like the block scene; Dirichlet conditions on
// named faces; a tissue material without viscosity; a Newton driver for static load steps.
#pragma once

#include <string>
#include <vector>

#include <petscvec.h>

#include "model/tet_mesh.hpp"
#include "physics/material/material.hpp"
#include "physics/mechanics/dirichlet.hpp"
#include "physics/mechanics/mechanics_system.hpp"

namespace needlefem::contact::testing {

// Grid coordinates on [0, length]: cells of `fine` up to `fine_extent`, then cells growing by
// `growth`, the coarse ones scaled so the last ends exactly at `length`.
std::vector<double> graded_coordinates(double fine, double fine_extent, double growth, double length);
// The same, fine at the far end (length - x of the above, reversed).
std::vector<double> graded_towards_end(double fine, double fine_extent, double growth, double length);

TetMesh structured_block(const std::vector<double>& xs, const std::vector<double>& ys, const std::vector<double>& zs);

// Adds u_c = field(X, t)_c on the given components of every node of `surface`.
void constrain(mechanics::DirichletConditions& conditions, const TetMesh& mesh, const mechanics::DofMap& dofs,
               const std::string& surface, const std::vector<int>& components, mechanics::DisplacementField field);

// Neo-Hookean (C10 = shear_modulus / 2) with bulk modulus K, no Prony terms.
material::Material neo_hookean(double shear_modulus, double bulk_modulus);

// Full Newton at time t from the current y (y' held at zero): the number of iterations after
// which the correction fell below 1e-10 of y, or -1 when that took more than `max_iterations`
// or the system failed (inverted element).
int solve_static(mechanics::MechanicsSystem& system, double t, Vec y, Vec ydot, int max_iterations = 30);

}  // namespace needlefem::contact::testing
