#include "core/modules/contact_response.h"

#include "core/modules/collider_motion.h"
#include "core/modules/shape_collider.h"

namespace neurocloth::contact_response {

ColliderFrame frame_over(const ModuleSpec& declared, const StepSpan& span) {
  ColliderFrame f;
  const ColliderMotion* motion = collider_motion(declared);
  f.moving = motion && motion->moves();
  f.start = collider_pose(declared, span.t0);
  f.end = f.moving ? collider_pose(declared, span.t0 + span.h) : f.start;
  f.h = span.h;
  return f;
}

// correct_contacts() backwards, each line undoing one of its lines, last first.
bool response_adjoint(const Contact& c, const Vec3& grad_phi, const Mat3& dn, const Vec3& p,
                      const Vec3& b, const Vec3& v, double thickness, double mu_k, double mu_s,
                      double h, Vec3& lp, Vec3& lv, Vec3& lb, double* l_mu) {
  const Vec3& n = c.normal;
  const double vn = v.dot(n);
  const Vec3 vt = v - vn * n;
  const double depth = thickness - c.phi;
  lb.setZero();
  if (!(c.phi < thickness + kTouch) || (depth <= 0.0 && vn >= 0.0)) return false;  // identity
  const bool push_by_depth = depth / h > -vn;
  const double dvn = std::max(-vn, depth / h);
  const double speed = vt.norm();
  const bool slides = !(speed <= mu_s * dvn) && 1.0 - mu_k * dvn / speed > 0.0;
  const double keep = slides ? 1.0 - mu_k * dvn / speed : 0.0;
  const Vec3 step = p - b;
  const double sn = step.dot(n);
  const Vec3 slip = step - sn * n;

  const Vec3 lp_out = lp, lv_out = lv;
  Vec3 ln = Vec3::Zero();
  double l_depth = 0, l_keep = 0, l_vn = 0;
  lv.setZero();
  // p' = p + max(depth, 0) n - (1 - keep) slip
  if (depth > 0.0) {
    l_depth += lp_out.dot(n);
    ln += depth * lp_out;
  }
  l_keep += lp_out.dot(slip);
  const Vec3 l_slip = -(1.0 - keep) * lp_out;
  // v' = max(vn, 0) n + keep vt
  if (vn > 0.0) {
    l_vn += lv_out.dot(n);
    ln += vn * lv_out;
  }
  l_keep += lv_out.dot(vt);
  Vec3 l_vt = keep * lv_out;
  // slip = step - (step.n) n, step = p - b
  const double l_sn = -l_slip.dot(n);
  ln += -sn * l_slip + l_sn * step;
  const Vec3 l_step = l_slip + l_sn * n;
  lp += l_step;
  lb = -l_step;
  // keep = 1 - mu_k dvn / |vt| while sliding
  double l_dvn = 0;
  if (slides) {
    if (l_mu) *l_mu -= l_keep * dvn / speed;
    l_dvn -= l_keep * mu_k / speed;
    l_vt += (l_keep * mu_k * dvn / (speed * speed * speed)) * vt;
  }
  // dvn = max(-vn, depth / h)
  if (push_by_depth)
    l_depth += l_dvn / h;
  else
    l_vn -= l_dvn;
  // vt = v - vn n, vn = v.n
  lv += l_vt;
  l_vn -= l_vt.dot(n);
  ln -= vn * l_vt;
  lv += l_vn * n;
  ln += l_vn * v;
  // depth = thickness - phi(p), n = n(p)
  lp += -l_depth * grad_phi + dn.transpose() * ln;
  return true;
}

}  // namespace neurocloth::contact_response
