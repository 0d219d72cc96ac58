// Equations: penalty_contact.hpp.
#include "physics/contact/penalty_contact.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "physics/elements/triangle_face.hpp"

namespace needlefem::contact {

namespace {

// Half-width b of the return map's blend from stick to slip, in units of s₀ (penalty_contact.hpp),
// and the elastic slip (1 + b) s₀ beyond which a point carries the Coulomb limit and is dragged.
constexpr double kSlipBlend = 1.0;
constexpr double kSlidingSlip = 1.0 + kSlipBlend;

using elements::kTriangleRule;
using elements::triangle_shape;
constexpr double kMetresPerMm = 1e-3;
// Augmented enforcement: at most this many multiplier updates over the motion (see
// ContactParameters::multiplier_update_interval).
constexpr double kMultiplierUpdatesPerMotion = 1000.0;

Point3 cross(const Point3& a, const Point3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

double dot(const Point3& a, const Point3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// ∂(P r)/∂x for P = I - n nᵀ(x) and r with ∂r/∂x = I (return map: r = x - a) or 0 (velocity law,
// whose r = v - w has its own x-dependence, -W, added by the caller):
//   identity ? P : 0,  - (n·r) G - n (rᵀ G).
Matrix3 projected_gradient(const ObstacleProjection& p, const Point3& r, bool identity) {
  Matrix3 D{};
  Point3 r_G{};  // rᵀ G
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j) r_G[k] += r[j] * p.normal_gradient[3 * j + k];
  const double n_r = dot(p.normal, r);
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k)
      D[3 * i + k] = (identity ? (i == k ? 1.0 : 0.0) - p.normal[i] * p.normal[k] : 0.0) -
                     n_r * p.normal_gradient[3 * i + k] - p.normal[i] * r_G[k];
  return D;
}

// Tangential traction of one point and its derivatives (position, velocity).
struct Tangential {
  Point3 traction{};
  Matrix3 d_position{}, d_velocity{};
  bool slipping = false;
};

Point3 difference(const Point3& a, const Point3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }

// P r = r - (n·r) n, the part of r tangent to the obstacle.
Point3 tangential_part(const Point3& n, const Point3& r) {
  const double n_r = dot(n, r);
  return {r[0] - n_r * n[0], r[1] - n_r * n[1], r[2] - n_r * n[2]};
}

// Slip velocity of a tissue point moving at v over the obstacle: r = v - w, v_T = P r, and (with
// the gradient) ∂v_T/∂x = -(n·r) G - n (rᵀ G) - P W. Shared by the velocity law and the rate
// strengthening.
struct SlipVelocity {
  Point3 relative{}, tangential{};
  Matrix3 gradient{};
};
SlipVelocity slip_velocity(const ObstacleProjection& p, const Point3& velocity, bool with_gradient) {
  SlipVelocity out;
  out.relative = difference(velocity, p.velocity);
  out.tangential = tangential_part(p.normal, out.relative);
  if (!with_gradient) return out;
  out.gradient = projected_gradient(p, out.relative, false);
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 3; ++j)
        out.gradient[3 * i + k] -= ((i == j ? 1.0 : 0.0) - p.normal[i] * p.normal[j]) * p.velocity_gradient[3 * j + k];
  return out;
}

// Return map with the allowed elastic slip s₀ (penalty_contact.hpp), C¹ across stick and slip:
//   t_T = -μ p φ(|g_T|/s₀) ĝ,  φ(x) = x (x <= 1 - b), x - (x - 1 + b)²/(4b) (|x - 1| < b), 1 (x >= 1 + b),
// b = kSlipBlend. Newton matrix, with s = |g_T|: -μ p [(φ/s) D + (φ'/s₀ - φ/s) ĝ ĝᵀ D] + μ p' (φ/s) g_T nᵀ.
struct SlipFraction {
  double value = 0.0, slope = 0.0;  // φ(x), φ'(x)
};
SlipFraction slip_fraction(double x) {
  constexpr double b = kSlipBlend;
  if (x <= 1.0 - b) return {x, 1.0};
  if (x >= 1.0 + b) return {1.0, 0.0};
  const double over = x - 1.0 + b;
  return {x - over * over / (4.0 * b), 1.0 - over / (2.0 * b)};
}

Tangential return_map(const ObstacleProjection& p, const Point3& position, const Point3& anchor,
                      const NormalPressure& normal, double mu, double allowed_slip, bool with_jacobian,
                      double pressure_coupling) {
  Tangential out;
  const Point3 r = difference(position, anchor), slip = tangential_part(p.normal, r);
  const double size = std::sqrt(dot(slip, slip)), x = size / allowed_slip;
  const SlipFraction phi = slip_fraction(x);
  out.slipping = x >= kSlidingSlip;
  // φ/s, which is 1/s₀ in the stick range (also at s = 0).
  const double per_slip = x <= 1.0 - kSlipBlend ? 1.0 / allowed_slip : phi.value / size;
  const double scale = mu * normal.pressure * per_slip;
  for (int i = 0; i < 3; ++i) out.traction[i] = -scale * slip[i];
  if (!with_jacobian) return out;
  const Matrix3 D = projected_gradient(p, r, true);
  const double stretch = x <= 1.0 - kSlipBlend ? 0.0 : mu * normal.pressure * (phi.slope / allowed_slip - per_slip);
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) {
      double along_slip = 0.0;  // (ĝ ĝᵀ D)_ik, the part of D that only stretches |g_T|
      if (stretch != 0.0)
        for (int j = 0; j < 3; ++j) along_slip += slip[i] * slip[j] / (size * size) * D[3 * j + k];
      out.d_position[3 * i + k] = pressure_coupling * mu * normal.stiffness * per_slip * slip[i] * p.normal[k] -
                                  scale * D[3 * i + k] - stretch * along_slip;
    }
  return out;
}

// Rate strengthening of the return map (penalty_contact.hpp), added to `out`: t = -β p_N v_T,
// ∂t/∂x = -β p_N ∂v_T/∂x + β p' v_T nᵀ, ∂t/∂v = -β p_N P.
void add_rate_strengthening(const ObstacleProjection& p, const Point3& velocity, const NormalPressure& normal,
                            double beta, bool with_jacobian, double pressure_coupling, Tangential& out) {
  const SlipVelocity slip = slip_velocity(p, velocity, with_jacobian);
  for (int i = 0; i < 3; ++i) out.traction[i] -= beta * normal.pressure * slip.tangential[i];
  if (!with_jacobian) return;
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) {
      out.d_position[3 * i + k] += -beta * normal.pressure * slip.gradient[3 * i + k] +
                                   pressure_coupling * beta * normal.stiffness * slip.tangential[i] * p.normal[k];
      out.d_velocity[3 * i + k] += -beta * normal.pressure * ((i == k ? 1.0 : 0.0) - p.normal[i] * p.normal[k]);
    }
}

// Velocity-regularised Coulomb law (penalty_contact.hpp); tangent per `tangent`.
Tangential velocity_law(const ObstacleProjection& p, const Point3& velocity, const NormalPressure& normal, double mu,
                        double eps_v, FrictionTangent tangent, bool with_jacobian, double pressure_coupling) {
  const double pressure = normal.pressure, normal_stiffness = normal.stiffness;
  Tangential out;
  const SlipVelocity slip_rate = slip_velocity(p, velocity, with_jacobian);
  const Point3& slip = slip_rate.tangential;
  const double s = std::sqrt(dot(slip, slip) + eps_v * eps_v);
  out.slipping = dot(slip, slip) > eps_v * eps_v;
  for (int i = 0; i < 3; ++i) out.traction[i] = -mu * pressure * slip[i] / s;
  if (!with_jacobian) return out;
  // T = (μ p / s)(I - v_T v_Tᵀ / s²).
  const double slip_curvature = tangent == FrictionTangent::consistent ? 1.0 : 0.0;
  const Matrix3& slip_gradient = slip_rate.gradient;
  Matrix3 T{};
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k)
      T[3 * i + k] = mu * pressure / s * ((i == k ? 1.0 : 0.0) - slip_curvature * slip[i] * slip[k] / (s * s));
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) {
      double T_slip = 0.0, T_P = 0.0;
      for (int j = 0; j < 3; ++j) {
        T_slip += T[3 * i + j] * slip_gradient[3 * j + k];
        T_P += T[3 * i + j] * ((j == k ? 1.0 : 0.0) - p.normal[j] * p.normal[k]);
      }
      out.d_position[3 * i + k] = -T_slip + pressure_coupling * mu * normal_stiffness * slip[i] / s * p.normal[k];
      out.d_velocity[3 * i + k] = -T_P;
    }
  return out;
}

}  // namespace

NormalPressure normal_pressure(double depth, double penalty, double smoothing_depth) {
  if (depth >= smoothing_depth) return {penalty * (depth - 0.5 * smoothing_depth), penalty};
  return {0.5 * penalty * depth * depth / smoothing_depth, penalty * depth / smoothing_depth};
}

ContactParameters contact_parameters_from_spec(const ContactSpec& spec, double reference_modulus, double history_end_s,
                                               long mesh_refinement_level) {
  ContactParameters p;
  p.friction_coefficient = spec.friction_coefficient;
  p.penalty_factor = spec.penalty_factor;
  p.penalty_smoothing = spec.penalty_smoothing;
  p.elastic_slip = spec.elastic_slip;
  p.rate_strengthening = spec.rate_strengthening_s_per_m;
  p.slip_velocity_regularisation = spec.slip_velocity_regularisation_mm_per_s * kMetresPerMm;
  p.reference_modulus = reference_modulus;
  p.face_size_scale = std::ldexp(1.0, static_cast<int>(mesh_refinement_level));
  p.friction_tangent = spec.friction_tangent;
  p.friction_law = spec.friction_law;
  p.normal_enforcement = spec.normal_enforcement;
  p.multiplier_update_interval = history_end_s / kMultiplierUpdatesPerMotion;
  return p;
}

PenaltyContact::PenaltyContact(const TetMesh& mesh, const std::string& surface,
                               std::shared_ptr<const RigidObstacle> obstacle, const ContactParameters& parameters)
    : mesh_(mesh), obstacle_(std::move(obstacle)), parameters_(parameters), nodes_per_face_(mesh.nodes_per_face()) {
  if (!(parameters.reference_modulus > 0.0) || !(parameters.penalty_factor > 0.0) ||
      !(parameters.slip_velocity_regularisation > 0.0) || parameters.friction_coefficient < 0.0)
    throw std::invalid_argument("PenaltyContact: modulus, penalty factor and slip regularisation must be positive, "
                                "friction coefficient non-negative");
  const auto found = mesh.surface_faces.find(surface);
  if (found == mesh.surface_faces.end()) throw std::runtime_error("the mesh has no surface '" + surface + "'");
  face_nodes_ = found->second;
  const int m = nodes_per_face_;
  std::array<double, 6> dN_dxi{}, dN_deta{};
  double mean_face_size = 0.0;
  for (std::size_t f = 0; f < face_nodes_.size() / m; ++f) {
    Face face;
    double area = 0.0;
    for (const auto& q : kTriangleRule) {
      FacePoint point;
      triangle_shape(m, q.xi, q.eta, point.shape.data(), dN_dxi.data(), dN_deta.data());
      Point3 tangent_xi{}, tangent_eta{};
      for (int a = 0; a < m; ++a)
        for (int c = 0; c < 3; ++c) {
          const double X = mesh.nodes[face_nodes_[f * m + a]][c];
          tangent_xi[c] += dN_dxi[a] * X;
          tangent_eta[c] += dN_deta[a] * X;
        }
      const Point3 normal = cross(tangent_xi, tangent_eta);
      point.area_weight = q.weight * std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
      Point3 X{};
      for (int a = 0; a < m; ++a)
        for (int c = 0; c < 3; ++c) X[c] += point.shape[a] * mesh.nodes[face_nodes_[f * m + a]][c];
      if (parameters.reference_gap_offset) point.gap_offset = obstacle_->project(X, 0.0).gap;
      point.anchor = obstacle_->to_body(X, 0.0);
      area += point.area_weight;
      face.points.push_back(point);
    }
    if (!(area > 0.0)) throw std::runtime_error(fmt::format("contact surface '{}': face {} has no area", surface, f));
    const double size = parameters.face_size_scale * std::sqrt(2.0 * area);
    face.penalty = parameters.penalty_factor * parameters.reference_modulus / size;
    face.smoothing_depth = parameters.penalty_smoothing * size / parameters.penalty_factor;
    mean_face_size += size / static_cast<double>(face_nodes_.size() / m);
    faces_.push_back(std::move(face));
  }
  elastic_slip_ = parameters.elastic_slip * mean_face_size;
}

FaceTerms PenaltyContact::face_terms(std::size_t face, const double* x, const double* v, double t, double cj,
                                     bool with_jacobian, const Point3& moment_point,
                                     NewtonMatrix form, int body) const {
  const int m = nodes_per_face_, n = 3 * m;
  const double mu = parameters_.friction_coefficient;
  const double penalty = faces_[face].penalty;
  const double coupling = form == NewtonMatrix::exact ? 1.0 : 0.0;  // friction's pressure coupling
  FaceTerms out;
  out.residual.assign(n, 0.0);
  if (with_jacobian) out.jacobian.assign(static_cast<std::size_t>(n) * n, 0.0);
  for (const FacePoint& point : faces_[face].points) {
    const Point3 position = point_position(point, x);
    const ObstacleProjection p = obstacle_->project(position, t);
    // Touching points (g = 0, e.g. every point of a surface that starts in contact) count as
    // closed: with the plain penalty (s = 0) their stiffness then enters the Newton matrix
    // evaluated at the start state, without which IDA's modified Newton never sees the contact it
    // is about to create.
    const double depth = effective_depth(point, p.gap - point.gap_offset, t);
    if (depth < 0.0) continue;
    const Point3& normal = p.normal;
    const NormalPressure normal_law = normal_pressure(depth, penalty, faces_[face].smoothing_depth);
    const double pressure = normal_law.pressure;
    Point3 velocity{};
    for (int a = 0; a < m; ++a)
      for (int c = 0; c < 3; ++c) velocity[c] += point.shape[a] * v[3 * a + c];
    Tangential tangential;
    if (parameters_.friction_law == FrictionLaw::return_map) {
      tangential = return_map(p, position, obstacle_->from_body(point.anchor, t), normal_law, mu,
                              elastic_slip_, with_jacobian, coupling);
      if (parameters_.rate_strengthening > 0.0)
        add_rate_strengthening(p, velocity, normal_law, parameters_.rate_strengthening, with_jacobian, coupling,
                               tangential);
    } else {
      tangential = velocity_law(p, velocity, normal_law, mu, parameters_.slip_velocity_regularisation,
                                parameters_.friction_tangent, with_jacobian, coupling);
    }
    Point3 traction;
    for (int i = 0; i < 3; ++i) traction[i] = pressure * normal[i] + tangential.traction[i];

    const double w = point.area_weight;
    if (body < 0 || p.body == body) {
      out.contact_area += w;
      if (tangential.slipping) out.slipping_area += w;
      Point3 arm;
      for (int i = 0; i < 3; ++i) arm[i] = position[i] - moment_point[i];
      const Point3 moment = cross(arm, traction);
      for (int i = 0; i < 3; ++i) {
        out.force_on_tissue[i] += w * traction[i];
        out.moment_on_tissue[i] += w * moment[i];
      }
    }
    for (int a = 0; a < m; ++a)
      for (int i = 0; i < 3; ++i) out.residual[3 * a + i] -= w * point.shape[a] * traction[i];
    if (!with_jacobian) continue;

    Matrix3 d_position;
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k)
        d_position[3 * i + k] = -normal_law.stiffness * normal[i] * normal[k] + pressure * p.normal_gradient[3 * i + k] +
                                tangential.d_position[3 * i + k];
    for (int a = 0; a < m; ++a)
      for (int b = 0; b < m; ++b) {
        const double factor = -w * point.shape[a] * point.shape[b];
        for (int i = 0; i < 3; ++i)
          for (int k = 0; k < 3; ++k)
            out.jacobian[static_cast<std::size_t>(3 * a + i) * n + 3 * b + k] +=
                factor * (d_position[3 * i + k] + cj * tangential.d_velocity[3 * i + k]);
      }
  }
  return out;
}

Point3 PenaltyContact::point_position(const FacePoint& point, const double* x) const {
  Point3 position{};
  for (int a = 0; a < nodes_per_face_; ++a)
    for (int c = 0; c < 3; ++c) position[c] += point.shape[a] * x[3 * a + c];
  return position;
}

double PenaltyContact::offset(const FacePoint& point, double t) const {
  if (parameters_.normal_enforcement == NormalEnforcement::penalty) return 0.0;
  double ramp = 1.0;
  if (ramp_duration_ > 0.0) ramp = std::clamp((t - ramp_start_) / ramp_duration_, 0.0, 1.0);
  return std::max(0.0, point.offset_start + ramp * point.offset_increment + (t - ramp_start_) * point.offset_rate);
}

double PenaltyContact::mean_offset(std::size_t face, double t) const {
  double sum = 0.0;
  for (const FacePoint& point : faces_[face].points) sum += offset(point, t);
  return sum / static_cast<double>(faces_[face].points.size());
}

void PenaltyContact::accept_step(double t, const double* y, const double* ydot, const mechanics::DofMap& dofs) {
  const bool anchors = parameters_.friction_law == FrictionLaw::return_map;
  const double step = t - last_update_;
  const bool augmented = parameters_.normal_enforcement == NormalEnforcement::augmented &&
                         step >= parameters_.multiplier_update_interval;
  if (!anchors && !augmented) return;
  std::vector<double> x(3 * nodes_per_face_), v(3 * nodes_per_face_);
  for (std::size_t f = 0; f < faces_.size(); ++f) {
    gather(f, y, ydot, dofs, x.data(), v.data());
    for (FacePoint& point : faces_[f].points) {
      const Point3 position = point_position(point, x.data());
      const ObstacleProjection p = obstacle_->project(position, t);
      const double gap = p.gap - point.gap_offset;
      const double offset_now = offset(point, t), depth = offset_now - gap;  // o(t_n), z
      if (augmented) {
        const double target = std::max(0.0, depth);  // z_n
        point.offset_start = offset_now;
        point.offset_increment = target - offset_now;
        point.offset_rate = step > 0.0 && target > 0.0 ? (target - point.target) / step : 0.0;
        point.target = target;
      }
      if (!anchors) continue;
      Point3 anchor = position;  // out of contact: re-anchor where the point is
      if (depth >= 0.0) {
        const Point3 slip = tangential_part(p.normal, difference(position, obstacle_->from_body(point.anchor, t)));
        const double size = std::sqrt(dot(slip, slip)), allowed = kSlidingSlip * elastic_slip_;
        const double kept = size > allowed ? allowed / size : 1.0;  // a slipping point drags its anchor along
        for (int i = 0; i < 3; ++i) anchor[i] -= kept * slip[i];
      }
      point.anchor = obstacle_->to_body(anchor, t);
    }
  }
  if (!augmented) return;
  ramp_start_ = t;
  ramp_duration_ = step;
  last_update_ = t;
}

void PenaltyContact::gather(std::size_t face, const double* y, const double* ydot, const mechanics::DofMap& dofs,
                            double* x, double* v) const {
  for (int a = 0; a < nodes_per_face_; ++a) {
    const int node = face_nodes(face)[a];
    for (int c = 0; c < 3; ++c) {
      x[3 * a + c] = mesh_.nodes[node][c] + y[dofs.dof(node, c)];
      v[3 * a + c] = ydot[dofs.dof(node, c)];
    }
  }
}

bool PenaltyContact::depends_on_rates() const {
  if (parameters_.friction_law == FrictionLaw::return_map) return parameters_.rate_strengthening > 0.0;
  return parameters_.friction_coefficient > 0.0;
}

ContactResultant PenaltyContact::resultant(double t, const double* y, const double* ydot,
                                           const mechanics::DofMap& dofs, const Point3& moment_point,
                                           int body) const {
  ContactResultant total;
  std::vector<double> x(3 * nodes_per_face_), v(3 * nodes_per_face_);
  for (std::size_t f = 0; f < faces_.size(); ++f) {
    gather(f, y, ydot, dofs, x.data(), v.data());
    const FaceTerms terms =
        face_terms(f, x.data(), v.data(), t, 0.0, false, moment_point, NewtonMatrix::exact, body);
    for (int i = 0; i < 3; ++i) {
      total.force_on_obstacle[i] -= terms.force_on_tissue[i];
      total.moment_on_obstacle[i] -= terms.moment_on_tissue[i];
    }
    total.contact_area += terms.contact_area;
  }
  return total;
}

void PenaltyContact::add_residual(double t, const double* y, const double* ydot, const mechanics::DofMap& dofs,
                                  double* f_u) const {
  std::vector<double> x(3 * nodes_per_face_), v(3 * nodes_per_face_);
  for (std::size_t f = 0; f < faces_.size(); ++f) {
    gather(f, y, ydot, dofs, x.data(), v.data());
    const FaceTerms terms = face_terms(f, x.data(), v.data(), t, 0.0, false);
    if (terms.contact_area == 0.0) continue;
    for (int a = 0; a < nodes_per_face_; ++a)
      for (int c = 0; c < 3; ++c) f_u[dofs.dof(face_nodes(f)[a], c)] += terms.residual[3 * a + c];
  }
}

void PenaltyContact::add_jacobian(double t, const double* y, const double* ydot, double cj,
                                  const mechanics::DofMap& dofs, Mat jacobian, NewtonMatrix form) const {
  std::vector<double> x(3 * nodes_per_face_), v(3 * nodes_per_face_);
  std::vector<PetscInt> blocks(nodes_per_face_);
  for (std::size_t f = 0; f < faces_.size(); ++f) {
    gather(f, y, ydot, dofs, x.data(), v.data());
    const FaceTerms terms = face_terms(f, x.data(), v.data(), t, cj, true, {}, form);
    if (terms.contact_area == 0.0) continue;
    for (int a = 0; a < nodes_per_face_; ++a) blocks[a] = dofs.node_dof[face_nodes(f)[a]] / 3;
    const PetscErrorCode code = MatSetValuesBlocked(jacobian, nodes_per_face_, blocks.data(), nodes_per_face_,
                                                    blocks.data(), terms.jacobian.data(), ADD_VALUES);
    if (code != 0) throw std::runtime_error(fmt::format("PETSc error {} in MatSetValuesBlocked (contact)", code));
  }
}

}  // namespace needlefem::contact
