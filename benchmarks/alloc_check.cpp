// Heap allocations made by the hot calls (the Reach loop must not allocate per iteration).
// Build and run from the repository root (not part of make bench: it links the core statically):
//   g++ -O2 -std=c++17 -I cpp/include -I /usr/include/eigen3 benchmarks/alloc_check.cpp \
//       cpp/src/chain.cpp cpp/src/reach.cpp cpp/src/task.cpp -lorocos-kdl -lpthread -o /tmp/alloc_check && /tmp/alloc_check
// It counts malloc and operator new calls (Eigen allocates through malloc) while they run.
#include "robokin/reach.hpp"
#include <cmath>
#include <cstdio>
#include <vector>
extern "C" void* __libc_malloc(size_t);
static long g_count = 0;
static bool g_on = false;
extern "C" void* malloc(size_t n) { if (g_on) ++g_count; return __libc_malloc(n); }
void* operator new(size_t n) { if (g_on) ++g_count; return __libc_malloc(n); }
using namespace robokin;
int main() {
  const double p = M_PI;
  Matrix4 t1 = Matrix4::Identity(); t1(0,3) = 1.5; Matrix4 t3 = Matrix4::Identity(); t3(0,3) = 1.0;
  std::vector<SegmentSpec> segs = {{JointType::Revolute, Eigen::Vector3d::UnitZ(), t1},
                                   {JointType::Prismatic, Eigen::Vector3d::UnitX(), Matrix4::Identity()},
                                   {JointType::Revolute, Eigen::Vector3d::UnitZ(), t3}};
  Vector lo(3), hi(3); lo << 0, 0, 0; hi << p/2, 1.5, p;
  Chain rpr = Chain::from_segments(segs, Matrix4::Identity(), lo, hi);
  for (int variant = 0; variant < 3; ++variant) {
    ReachOptions o;
    if (variant == 1) o.nullspace_weights = joint_limit_weights(rpr);
    if (variant == 2) o.damping = 1e-3;
    Reacher reacher(rpr, Task::XY, o);
    Vector q0(3); q0 << p/2, 0.5, p/2;
    const int K = 10000;
    std::vector<Target> targets(K);
    Eigen::Vector2d a(-1, 2), b(1.5, 1.0);
    for (int k = 0; k < K; ++k) { targets[k].task = Task::XY; targets[k].value.setZero(); targets[k].value.head<2>() = a + (b - a) * (k / double(K - 1)); }
    std::vector<double> qo(3 * K), err(K); std::vector<int> it(K); std::vector<char> conv(K);
    g_count = 0; g_on = true;
    reacher.track(targets.data(), K, q0, qo.data(), err.data(), reinterpret_cast<bool*>(conv.data()), it.data());
    g_on = false;
    long iters = 0; for (int k = 0; k < K; ++k) iters += it[k];
    printf("track variant %d: %d points, %ld iterations, %ld heap allocations\n", variant, K, iters, g_count);
  }
  Rigid T; double J[18]; std::vector<double> out(16 * 100000), q(3 * 100000, 0.3);
  g_count = 0; g_on = true;
  for (int i = 0; i < 1000; ++i) { rpr.fk(q.data(), T); rpr.fk_jacobian(q.data(), T, J); }
  rpr.fk_batch(q.data(), 100000, out.data());
  g_on = false;
  printf("1000 fk + 1000 fk_jacobian + a 100000 batch (threads): %ld heap allocations\n", g_count);
}
