// Loads the installed atwood.json through Reeve::scene, steps it 0.5 s and
// checks the heavy box's acceleration against a = (m2 - m1) g / (m1 + m2 +
// M/2) = 2.4525 m/s^2 (1 kg, 2 kg, a 2 kg solid wheel). Exit 0 if within 1 %.
#include <cmath>
#include <cstdio>

#include "reeve/scene/scene.h"

int main() {
  reeve::Scene s = reeve::loadScene(ATWOOD_JSON);
  const auto heavy = s.world->findBody("heavy");
  if (!heavy) {
    std::fprintf(stderr, "consumer: atwood.json has no body \"heavy\"\n");
    return 1;
  }
  const double y0 = s.world->body(*heavy).x.y();
  const int frames = static_cast<int>(std::lround(0.5 * s.frame_rate_hz));
  for (int f = 0; f < frames; ++f) s.world->step(1.0 / s.frame_rate_hz);
  const double t = s.world->time();
  const double a = 2.0 * (y0 - s.world->body(*heavy).x.y()) / (t * t);
  const double expected = (2.0 - 1.0) * 9.81 / (1.0 + 2.0 + 1.0);
  std::printf("consumer: %s, t = %.4f s, a = %.5f m/s^2 (closed form %.5f)\n", s.name.c_str(), t, a, expected);
  return std::abs(a - expected) <= 0.01 * expected ? 0 : 1;
}
