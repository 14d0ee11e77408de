// Transcription of the text's program; each statement is annotated with the Python it stands for.
// numpy evaluates element-wise left to right without fusing, so each line below does the same.
#include "rod_text_oracle.h"

#include <array>
#include <cmath>

namespace rbs_test {
namespace {

using Vec3 = std::array<double, 3>;

Vec3 add(const Vec3& a, const Vec3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec3 scale(double s, const Vec3& a) { return {s * a[0], s * a[1], s * a[2]}; }
Vec3 divide(const Vec3& a, double s) { return {a[0] / s, a[1] / s, a[2] / s}; }

// numpy.cross for 3-vectors: cp0 = a1*b2 - a2*b1, cp1 = a2*b0 - a0*b2, cp2 = a0*b1 - a1*b0.
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// f = -k*dr*(dr<0.0)*array([0,1,0]): ((-k)*dr) times 1.0 or 0.0, then times the int vector (0, 1, 0).
Vec3 floorForce(double k, double dr) {
  const double s = (-k * dr) * (dr < 0.0 ? 1.0 : 0.0);
  return scale(s, Vec3{0.0, 1.0, 0.0});
}

// The body of `for i in range(n-1)`, for end A then end B, as in the text.
void textStep(const TextParams& p, double I, std::vector<Vec3>& r, std::vector<Vec3>& v,
              std::vector<double>& theta, std::vector<double>& omega, std::vector<double>& t, std::size_t i) {
  const Vec3 yhat{0.0, 1.0, 0.0};
  Vec3 fnet{0.0, 0.0, 0.0};                                   // fnet = array([0,0,0])
  Vec3 tnet{0.0, 0.0, 0.0};                                   // tnet = 0.0 (becomes 0.0 + torque)
  const Vec3 u{std::cos(theta[i]), std::sin(theta[i]), 0.0};  // u = array([cos, sin, 0])
  Vec3 rr = add(r[i], scale(0.5 * p.L, u));                   // rr = r[i] + 0.5*L*u
  double dr = rr[1];                                          // dr = rr[1]
  Vec3 f = floorForce(p.k, dr);                               // f = -k*dr*(dr<0.0)*[0,1,0]
  fnet = add(fnet, f);                                        // fnet = fnet + f
  Vec3 torque = cross(sub(rr, r[i]), f);                      // torque = cross((rr-r[i]),f)
  tnet = add(tnet, torque);                                   // tnet = tnet + torque
  rr = sub(r[i], scale(0.5 * p.L, u));                        // rr = r[i] - 0.5*L*u
  dr = rr[1];
  f = floorForce(p.k, dr);
  fnet = add(fnet, f);
  torque = cross(sub(rr, r[i]), f);
  tnet = add(tnet, torque);
  fnet = sub(fnet, scale(p.m * p.g, yhat));       // fnet = fnet - m*g*[0,1,0]
  const Vec3 a = divide(fnet, p.m);               // a = fnet/m
  v[i + 1] = add(v[i], scale(p.dt, a));           // v[i+1] = v[i] + a*dt
  r[i + 1] = add(r[i], scale(p.dt, v[i + 1]));    // r[i+1] = r[i] + v[i+1]*dt
  const double alphaz = tnet[2] / I;              // alphaz = tnet[2]/I
  omega[i + 1] = omega[i] + alphaz * p.dt;        // omega[i+1] = omega[i] + alphaz*dt
  theta[i + 1] = theta[i] + omega[i + 1] * p.dt;  // theta[i+1] = theta[i] + omega[i+1]*dt
  t[i + 1] = t[i] + p.dt;                         // t[i+1] = t[i] + dt
}

}  // namespace

int textSampleCount(const TextParams& p) {
  return static_cast<int>(std::round(p.time / p.dt));  // n = int(round(time/dt))
}

std::vector<OracleSample> runTextProgram(double theta0, int n_samples, const TextParams& p) {
  const std::size_t n = static_cast<std::size_t>(n_samples < 0 ? textSampleCount(p) : n_samples);
  if (n == 0) return {};
  const double I = (1.0 / 12.0) * p.m * std::pow(p.L, 2.0);  // I = (1.0/12.0)*m*L**2
  std::vector<Vec3> r(n, Vec3{0.0, 0.0, 0.0}), v(n, Vec3{0.0, 0.0, 0.0});
  std::vector<double> theta(n, 0.0), omega(n, 0.0), t(n, 0.0);
  r[0] = {0.0, p.h0, 0.0};  // r[0] = array([0,h0,0])
  v[0] = {p.v0, 0.0, 0.0};  // v[0] = array([v0,0,0])
  theta[0] = theta0;        // theta[0] = 2*pi*random.rand(1) in the text
  for (std::size_t i = 0; i + 1 < n; ++i) textStep(p, I, r, v, theta, omega, t, i);

  std::vector<OracleSample> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    out[i] = {t[i], r[i][0], r[i][1], theta[i], v[i][0], v[i][1], omega[i]};
  }
  return out;
}

}  // namespace rbs_test
