// Sections (paper sec. 3.2, 3.4, Fig. 5-6): convex hulls, tangents from a
// point and between sections, distances along the boundary and area
// moments, each checked against geometry or a closed form.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

#include "reeve/cable/section.h"

namespace reeve::test_section {
namespace {

constexpr double kPi = std::numbers::pi;

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
Vec2 perp(const Vec2& v) { return Vec2(-v.y(), v.x()); }
Vec2 rotated(const Vec2& v, double angle) {
  return Vec2(std::cos(angle) * v.x() - std::sin(angle) * v.y(),
              std::sin(angle) * v.x() + std::cos(angle) * v.y());
}

Section rotatedSection(const Section& s, double angle) {
  std::vector<Vec2> v;
  for (const Vec2& p : s.vertices) v.push_back(rotated(p, angle));
  return Section::polygon(v);
}

Section regularPolygon(int n, double circumradius) {
  std::vector<Vec2> v;
  for (int k = 0; k < n; ++k) v.push_back(rotated(Vec2(circumradius, 0.0), 2.0 * kPi * k / n));
  return Section::polygon(v);
}

// The hull of a random cloud in a disc of random radius.
Section randomPolygon(std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double radius = 0.3 + 1.7 * unit(rng);
  const int n = 3 + static_cast<int>(unit(rng) * 12);
  for (;;) {
    std::vector<Vec2> points;
    for (int k = 0; k < n; ++k)
      points.push_back(radius * std::sqrt(unit(rng)) * rotated(Vec2(1, 0), 2 * kPi * unit(rng)));
    try {
      return Section::polygon(points);
    } catch (const std::invalid_argument&) {
    }
  }
}

Section randomSection(std::mt19937& rng, Section::Kind kind) {
  if (kind == Section::Kind::Polygon) return randomPolygon(rng);
  return Section::circle(std::uniform_real_distribution<double>(0.1, 2.0)(rng));
}

double extent(const Section& s) {
  if (s.kind == Section::Kind::Circle) return s.radius;
  double r = 0.0;
  for (const Vec2& v : s.vertices) r = std::max(r, v.norm());
  return r;
}

// Walking along a span with unit direction t, a section wrapped
// counter-clockwise (orientation +1) lies on the left: a ccw walk around a
// circle has the centre on the left, and the span continues that walk along
// the tangent. For -1 it lies on the right. So o * cross(t, x - a) >= 0 for
// every point x of the section, with a on the span line.
void expectOnSide(const Section& s, const Vec2& c, int o, const Vec2& a, const Vec2& t) {
  if (s.kind == Section::Kind::Circle) {
    // The nearest point of the disc to the line is at distance o cross - r.
    EXPECT_GE(o * cross(t, c - a) - s.radius, -1e-9) << "orientation " << o;
    return;
  }
  for (const Vec2& v : s.vertices) EXPECT_GE(o * cross(t, c + v - a), -1e-9) << "orientation " << o;
}

// `p` is a tangent point of the span (unit direction t) on section s at c:
// on the section, the section on the orientation's side, and for a circle
// the travel direction o perp(outward normal) equal to t (wrap sense).
void expectTangentPoint(const Section& s, const Vec2& c, int o, const Vec2& p, const Vec2& t) {
  if (s.kind == Section::Kind::Circle) {
    const Vec2 radial = p - c;
    EXPECT_NEAR(radial.norm(), s.radius, 1e-9);
    EXPECT_NEAR((o * perp(radial / s.radius) - t).norm(), 0.0, 1e-9) << "orientation " << o;
  } else {
    const bool is_vertex = std::any_of(s.vertices.begin(), s.vertices.end(),
                                       [&](const Vec2& v) { return (c + v - p).norm() < 1e-12; });
    EXPECT_TRUE(is_vertex);
  }
  expectOnSide(s, c, o, p, t);
}

// ---------------------------------------------------------------- hull

TEST(SectionHull, RandomCloudsGiveStrictlyConvexCcwHullsContainingEveryPoint) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> pos(-2.0, 2.0);
  std::uniform_int_distribution<int> count(3, 60);
  for (int trial = 0; trial < 500; ++trial) {
    std::vector<Vec2> points;
    const int n = count(rng);
    for (int k = 0; k < n; ++k) points.emplace_back(pos(rng), pos(rng));
    // Duplicates and points on the segments between cloud points.
    points.push_back(points[0]);
    points.push_back(0.5 * (points[1] + points[2]));
    const Section s = Section::polygon(points);
    ASSERT_EQ(s.kind, Section::Kind::Polygon);
    const std::vector<Vec2>& v = s.vertices;
    ASSERT_GE(v.size(), 3u);
    const std::size_t m = v.size();
    for (std::size_t i = 0; i < m; ++i) {
      // Strict left turn at every vertex: convex, ccw, no collinear vertex.
      EXPECT_GT(cross(v[(i + 1) % m] - v[i], v[(i + 2) % m] - v[(i + 1) % m]), 0.0);
      // Every hull vertex is an input point.
      EXPECT_TRUE(std::find(points.begin(), points.end(), v[i]) != points.end());
      // Every input point is left of or on every edge.
      for (const Vec2& p : points) EXPECT_GE(cross(v[(i + 1) % m] - v[i], p - v[i]), -1e-12);
    }
  }
}

TEST(SectionHull, DropsCollinearAndDuplicatePoints) {
  // A square's corners, edge midpoints, interior points and repeats.
  std::vector<Vec2> points;
  for (int i = -2; i <= 2; ++i)
    for (int j = -2; j <= 2; ++j) points.emplace_back(i, j);
  points.emplace_back(2, 2);
  const Section s = Section::polygon(points);
  ASSERT_EQ(s.vertices.size(), 4u);
  for (const Vec2& v : s.vertices) {
    EXPECT_EQ(std::abs(v.x()), 2.0);
    EXPECT_EQ(std::abs(v.y()), 2.0);
  }
  EXPECT_DOUBLE_EQ(s.perimeter(), 16.0);
  const Section box = boxSection(0.5, 0.25);
  EXPECT_EQ(box.vertices.size(), 4u);
  EXPECT_DOUBLE_EQ(box.perimeter(), 3.0);
}

TEST(SectionHull, ZeroAreaAndBadInputThrow) {
  EXPECT_THROW(Section::polygon({}), std::invalid_argument);
  EXPECT_THROW(Section::polygon({Vec2(1, 1)}), std::invalid_argument);
  EXPECT_THROW(Section::polygon({Vec2(0, 0), Vec2(1, 1), Vec2(0, 0)}), std::invalid_argument);
  EXPECT_THROW(Section::polygon({Vec2(0, 0), Vec2(1, 1), Vec2(2, 2), Vec2(-3, -3)}),
               std::invalid_argument);
  EXPECT_THROW(Section::polygon({Vec2(0, 0), Vec2(1, 0), Vec2(0, std::nan(""))}),
               std::invalid_argument);
  EXPECT_THROW(Section::circle(0.0), std::invalid_argument);
  EXPECT_THROW(Section::circle(-1.0), std::invalid_argument);
  EXPECT_THROW(boxSection(0.0, 1.0), std::invalid_argument);
}

// ------------------------------------------------------ tangent from a point

TEST(SectionTangentFromPoint, PolygonVertexSupportsTheSpanAndMatchesBruteForce) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> pos(-4.0, 4.0);
  int unique = 0;
  for (int trial = 0; trial < 1000; ++trial) {
    const Section s = randomPolygon(rng);
    const Vec2 p(pos(rng), pos(rng));
    for (int o : {-1, 1})
      for (bool leaving : {false, true}) {
        const auto q = tangentFromPoint(s, p, o, leaving);
        bool inside = true;
        for (std::size_t i = 0; i < s.vertices.size(); ++i)
          inside &= cross(s.vertices[(i + 1) % s.vertices.size()] - s.vertices[i],
                          p - s.vertices[i]) >= 0;
        ASSERT_EQ(q.has_value(), !inside);
        if (!q) continue;
        const Vec2 t = (leaving ? Vec2(p - *q) : Vec2(*q - p)).normalized();
        expectTangentPoint(s, Vec2::Zero(), o, *q, t);
        // Brute force: the vertices through which the line from p has the
        // whole polygon on the orientation's side.
        std::vector<Vec2> candidates;
        for (const Vec2& cand : s.vertices) {
          const Vec2 tc = (leaving ? Vec2(p - cand) : Vec2(cand - p)).normalized();
          const bool ok = std::all_of(s.vertices.begin(), s.vertices.end(), [&](const Vec2& v) {
            return o * cross(tc, v - cand) >= -1e-12;
          });
          if (ok) candidates.push_back(cand);
        }
        EXPECT_TRUE(std::find(candidates.begin(), candidates.end(), *q) != candidates.end());
        if (candidates.size() == 1) ++unique;
      }
  }
  EXPECT_GT(unique, 1000);
}

TEST(SectionTangentFromPoint, EdgeThroughThePointTouchesAtItsNearerEnd) {
  const Section box = boxSection(1.0, 0.5);
  // From (4, -0.5) the bottom edge lies along the span line.
  const auto q = tangentFromPoint(box, Vec2(4.0, -0.5), 1, true);
  ASSERT_TRUE(q);
  EXPECT_EQ(*q, Vec2(1.0, -0.5));
  // Inside and on the boundary: no tangent.
  EXPECT_FALSE(tangentFromPoint(box, Vec2(0.2, 0.1), 1, true));
  EXPECT_FALSE(tangentFromPoint(box, Vec2(1.0, 0.0), 1, false));
  EXPECT_FALSE(tangentFromPoint(box, Vec2(1.0, 0.5), -1, true));
  EXPECT_FALSE(tangentFromPoint(Section::circle(1.0), Vec2(0.6, 0.8), 1, true));
  EXPECT_FALSE(tangentFromPoint(Section::circle(1.0), Vec2::Zero(), 1, true));
}

TEST(SectionTangentFromPoint, CircleEqualsCommonTangentWithAPoint) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> pos(-4.0, 4.0), rad(0.1, 2.0);
  for (int trial = 0; trial < 1000; ++trial) {
    const Section s = Section::circle(rad(rng));
    const Vec2 p(pos(rng), pos(rng));
    if (p.norm() <= s.radius * 1.001) continue;
    for (int o : {-1, 1}) {
      const auto out = tangentFromPoint(s, p, o, true);
      const auto in = tangentFromPoint(s, p, o, false);
      const auto ref_out = commonTangent({Vec2::Zero(), s.radius, o}, {p, 0.0, 1});
      const auto ref_in = commonTangent({p, 0.0, 1}, {Vec2::Zero(), s.radius, o});
      ASSERT_TRUE(out && in && ref_out && ref_in);
      EXPECT_NEAR((*out - ref_out->on_from).norm(), 0.0, 1e-15);
      EXPECT_NEAR((*in - ref_in->on_to).norm(), 0.0, 1e-15);
      expectTangentPoint(s, Vec2::Zero(), o, *out, (p - *out).normalized());
      expectTangentPoint(s, Vec2::Zero(), o, *in, (*in - p).normalized());
    }
  }
}

// ----------------------------------------------------- tangent of two sections

struct Pair {
  Section from, to;
  Vec2 c_from, c_to;
};

// Every vertex pair (i, j) whose line has each polygon on its orientation's side.
std::vector<std::pair<Vec2, Vec2>> bruteForceTangents(const Pair& q, int o_from, int o_to) {
  std::vector<std::pair<Vec2, Vec2>> found;
  for (const Vec2& vf : q.from.vertices)
    for (const Vec2& vt : q.to.vertices) {
      const Vec2 a = q.c_from + vf, b = q.c_to + vt;
      if ((b - a).norm() < 1e-9) continue;
      const Vec2 t = (b - a).normalized();
      bool ok = true;
      for (const Vec2& v : q.from.vertices) ok &= o_from * cross(t, q.c_from + v - a) >= -1e-12;
      for (const Vec2& v : q.to.vertices) ok &= o_to * cross(t, q.c_to + v - a) >= -1e-12;
      if (ok) found.emplace_back(a, b);
    }
  return found;
}

void expectValidSectionTangent(const Pair& q, int o_from, int o_to, const TangentPoints& tp) {
  const Vec2 span = tp.on_to - tp.on_from;
  ASSERT_GT(span.norm(), 1e-9);
  const Vec2 t = span.normalized();
  expectTangentPoint(q.from, q.c_from, o_from, tp.on_from, t);
  expectTangentPoint(q.to, q.c_to, o_to, tp.on_to, t);
}

// Random pairs whose sections are apart, so all four tangents exist.
Pair randomSeparatedPair(std::mt19937& rng, Section::Kind kf, Section::Kind kt) {
  std::uniform_real_distribution<double> pos(-5.0, 5.0);
  for (;;) {
    Pair q{randomSection(rng, kf), randomSection(rng, kt), Vec2(pos(rng), pos(rng)),
           Vec2(pos(rng), pos(rng))};
    if ((q.c_to - q.c_from).norm() > extent(q.from) + extent(q.to) + 1e-3) return q;
  }
}

TEST(SectionTangent, SeparatedPairsOfEveryKindAndOrientation) {
  using K = Section::Kind;
  std::mt19937 rng(13);
  int max_rounds = 0;
  for (auto [kf, kt] : {std::pair{K::Circle, K::Polygon}, std::pair{K::Polygon, K::Circle},
                        std::pair{K::Polygon, K::Polygon}, std::pair{K::Circle, K::Circle}})
    for (int trial = 0; trial < 500; ++trial) {
      const Pair q = randomSeparatedPair(rng, kf, kt);
      for (int o_from : {-1, 1})
        for (int o_to : {-1, 1}) {
          int rounds = -1;
          const auto tp = sectionTangent(q.from, q.c_from, o_from, q.to, q.c_to, o_to, &rounds);
          ASSERT_TRUE(tp);
          ASSERT_LT(rounds, 100);
          max_rounds = std::max(max_rounds, rounds);
          expectValidSectionTangent(q, o_from, o_to, *tp);
          if (kf == K::Circle && kt == K::Circle) {
            const auto ref =
                commonTangent({q.c_from, q.from.radius, o_from}, {q.c_to, q.to.radius, o_to});
            ASSERT_TRUE(ref);
            EXPECT_NEAR((tp->on_from - ref->on_from).norm(), 0.0, 1e-15);
            EXPECT_NEAR((tp->on_to - ref->on_to).norm(), 0.0, 1e-15);
          }
          if (kf == K::Polygon && kt == K::Polygon) {
            const auto brute = bruteForceTangents(q, o_from, o_to);
            ASSERT_EQ(brute.size(), 1u);
            EXPECT_EQ(tp->on_from, brute[0].first);
            EXPECT_EQ(tp->on_to, brute[0].second);
          }
        }
    }
  RecordProperty("max_rounds", max_rounds);
}

TEST(SectionTangent, OverlappingPolygonsFindATangentExactlyWhenOneExists) {
  // Close pairs: sections overlap or nest. The iteration must succeed
  // exactly when some vertex pair supports both polygons on the right sides,
  // and return one of those pairs.
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> pos(-1.5, 1.5);
  int found = 0, absent = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Pair q{randomPolygon(rng), randomPolygon(rng), Vec2(pos(rng), pos(rng)),
                 Vec2(pos(rng), pos(rng))};
    for (int o_from : {-1, 1})
      for (int o_to : {-1, 1}) {
        int rounds = -1;
        const auto tp = sectionTangent(q.from, q.c_from, o_from, q.to, q.c_to, o_to, &rounds);
        ASSERT_LT(rounds, 100);
        const auto brute = bruteForceTangents(q, o_from, o_to);
        ASSERT_EQ(tp.has_value(), !brute.empty()) << "trial " << trial;
        if (!tp) {
          ++absent;
          continue;
        }
        ++found;
        expectValidSectionTangent(q, o_from, o_to, *tp);
        EXPECT_TRUE(std::find(brute.begin(), brute.end(), std::pair{tp->on_from, tp->on_to}) !=
                    brute.end());
      }
  }
  EXPECT_GT(found, 1000);
  EXPECT_GT(absent, 1000);
}

TEST(SectionTangent, OverlappingCirclePolygonPairsAreValidWhenFound) {
  using K = Section::Kind;
  std::mt19937 rng(19);
  std::uniform_real_distribution<double> pos(-1.5, 1.5);
  int found = 0;
  for (auto [kf, kt] : {std::pair{K::Circle, K::Polygon}, std::pair{K::Polygon, K::Circle}})
    for (int trial = 0; trial < 1000; ++trial) {
      const Pair q{randomSection(rng, kf), randomSection(rng, kt), Vec2(pos(rng), pos(rng)),
                   Vec2(pos(rng), pos(rng))};
      for (int o : {-1, 1}) {
        // Equal orientations: an outer tangent exists unless one section
        // holds the other, i.e. unless every vertex is inside the circle or
        // the circle is inside the polygon.
        const Section& poly = kf == K::Polygon ? q.from : q.to;
        const Section& circ = kf == K::Circle ? q.from : q.to;
        const Vec2 c_poly = kf == K::Polygon ? q.c_from : q.c_to;
        const Vec2 c_circ = kf == K::Circle ? q.c_from : q.c_to;
        bool vertex_outside = false, circle_outside = false;
        for (std::size_t i = 0; i < poly.vertices.size(); ++i) {
          const Vec2 a = c_poly + poly.vertices[i];
          const Vec2 e = (c_poly + poly.vertices[(i + 1) % poly.vertices.size()] - a).normalized();
          vertex_outside |= (a - c_circ).norm() > circ.radius + 1e-6;
          circle_outside |= cross(e, c_circ - a) < circ.radius - 1e-6;
        }
        int rounds = -1;
        const auto tp = sectionTangent(q.from, q.c_from, o, q.to, q.c_to, o, &rounds);
        ASSERT_LT(rounds, 100);
        EXPECT_EQ(tp.has_value(), vertex_outside && circle_outside) << "trial " << trial;
        if (!tp) continue;
        ++found;
        expectValidSectionTangent(q, o, o, *tp);
      }
    }
  EXPECT_GT(found, 1000);
}

TEST(SectionTangent, AlignedBoxesSpanBetweenTheNearerCorners) {
  // The bottom edges of two boxes are collinear: the span runs between the
  // facing corners, the free part of the cable.
  const Section box = boxSection(0.5, 0.5);
  int rounds = 0;
  const auto tp = sectionTangent(box, Vec2(0, 0), 1, box, Vec2(3, 0), 1, &rounds);
  ASSERT_TRUE(tp);
  EXPECT_EQ(tp->on_from, Vec2(0.5, -0.5));
  EXPECT_EQ(tp->on_to, Vec2(2.5, -0.5));
  EXPECT_LT(rounds, 5);
  // A box touching another at a corner has no crossed tangent.
  EXPECT_FALSE(sectionTangent(box, Vec2(0, 0), 1, box, Vec2(1, 1), -1));
}

// ------------------------------------------------- distances along the boundary

// Turns `s` by one revolution in `steps` steps of `sense` (+1 ccw) about its
// origin, with the span leaving it towards a fixed far point, and returns
// the cable paid out: the sum of sectionSurfaceDistance between the turned
// old anchor and the new tangent point (Alg. 1 line 4). Each step pays out
// nothing or whole edges, since the tangent point is always a vertex.
double payOutOverOneTurn(const Section& s, int orientation, int sense, int steps) {
  const Vec2 far(7.0, 0.3);
  const double step = sense * 2.0 * kPi / steps;
  Vec2 anchor = *tangentFromPoint(s, far, orientation, true);
  double paid = 0.0;
  for (int k = 1; k <= steps; ++k) {
    const Section turned = rotatedSection(s, k * step);
    const Vec2 old_anchor = rotated(anchor, step);
    const auto fresh = tangentFromPoint(turned, far, orientation, true);
    if (!fresh) ADD_FAILURE() << "no tangent";
    paid += sectionSurfaceDistance(turned, old_anchor, *fresh, orientation);
    anchor = *fresh;
  }
  return paid;
}

TEST(SectionSurfaceDistance, SquareAndHexagonPayOutTheirPerimeterPerTurn) {
  const double a = 0.7;
  const Section square = Section::polygon({Vec2(0, 0), Vec2(a, 0), Vec2(a, a), Vec2(0, a)});
  const Section hexagon = regularPolygon(6, 0.4);
  for (const Section* s : {&square, &hexagon}) {
    const Section centred = Section::polygon([&] {
      std::vector<Vec2> v;
      Vec2 mean = Vec2::Zero();  // vertex mean: inside, for both shapes the centre
      for (const Vec2& p : s->vertices) mean += p / static_cast<double>(s->vertices.size());
      for (const Vec2& p : s->vertices) v.push_back(p - mean);
      return v;
    }());
    for (const Section* turned : {s, &centred})
      for (int o : {-1, 1})
        for (int sense : {-1, 1}) {
          // Turning in the orientation's sense pays cable out into the span.
          EXPECT_NEAR(payOutOverOneTurn(*turned, o, sense, 997), o * sense * s->perimeter(), 1e-9)
              << "orientation " << o << " sense " << sense;
        }
  }
  EXPECT_NEAR(square.perimeter(), 4 * a, 1e-15);
  EXPECT_NEAR(hexagon.perimeter(), 6 * 0.4, 1e-15);
}

TEST(SectionBoundary, CircleDistancesAreRadiusTimesAngle) {
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> angle(-kPi, kPi), rad(0.1, 3.0), small(-3.0, 3.0);
  for (int trial = 0; trial < 2000; ++trial) {
    const double r = rad(rng);
    const Section s = Section::circle(r);
    const double a1 = angle(rng), a2 = a1 + small(rng);
    const Vec2 p1 = r * Vec2(std::cos(a1), std::sin(a1)), p2 = r * Vec2(std::cos(a2), std::sin(a2));
    double expected_pos = std::fmod(a1 + 2 * kPi, 2 * kPi) * r;
    EXPECT_NEAR(boundaryPosition(s, p1), expected_pos, 1e-12);
    EXPECT_NEAR(boundaryPosition(s, 3.0 * p1), expected_pos, 1e-12);  // off the boundary
    for (int o : {-1, 1}) {
      // From new (p2) to old (p1) is a1 - a2 counter-clockwise, |.| < pi.
      EXPECT_NEAR(sectionSurfaceDistance(s, p1, p2, o), o * r * (a1 - a2), 1e-12);
      const double arc = sectionWrappedArc(s, p1, p2, o), ref = o * r * (a2 - a1);
      // Equal, or one just below a full turn and the other just above zero.
      EXPECT_NEAR(std::remainder(arc - ref, 2 * kPi * r), 0.0, 1e-12);
      EXPECT_GE(arc, 0.0);
      EXPECT_LT(arc, 2 * kPi * r);
    }
  }
}

// A random point on the boundary of polygon s.
Vec2 randomBoundaryPoint(std::mt19937& rng, const Section& s) {
  const std::size_t n = s.vertices.size();
  const std::size_t i = std::uniform_int_distribution<std::size_t>(0, n - 1)(rng);
  const double t = std::uniform_real_distribution<double>(0.0, 1.0)(rng);
  return s.vertices[i] + t * (s.vertices[(i + 1) % n] - s.vertices[i]);
}

double distanceToBoundary(const Section& s, const Vec2& x) {
  double best = INFINITY;
  for (std::size_t i = 0; i < s.vertices.size(); ++i) {
    const Vec2 a = s.vertices[i], e = s.vertices[(i + 1) % s.vertices.size()] - a;
    const double t = std::clamp((x - a).dot(e) / e.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (a + t * e - x).norm());
  }
  return best;
}

double polylineLength(const std::vector<Vec2>& points) {
  double length = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) length += (points[i] - points[i - 1]).norm();
  return length;
}

TEST(SectionBoundary, PolygonDistancesArcsAndArcPointsAreConsistent) {
  std::mt19937 rng(29);
  for (int trial = 0; trial < 500; ++trial) {
    const Section s = randomPolygon(rng);
    const double perimeter = s.perimeter();
    const Vec2 p = randomBoundaryPoint(rng, s), q = randomBoundaryPoint(rng, s);
    for (int o : {-1, 1}) {
      const double arc = sectionWrappedArc(s, p, q, o), back = sectionWrappedArc(s, q, p, o);
      EXPECT_NEAR(arc + back, perimeter, 1e-12);
      EXPECT_NEAR(sectionWrappedArc(s, p, q, -o), back, 1e-12);
      // surfaceDist: from new (q) to old (p) in the orientation's sense is
      // the wrapped arc from q to p, taken the shorter way.
      const double d = sectionSurfaceDistance(s, p, q, o);
      EXPECT_LE(std::abs(d), perimeter / 2 + 1e-12);
      EXPECT_NEAR(d, back <= perimeter / 2 ? back : back - perimeter, 1e-12);
      // The drawn cable follows the boundary: its length is the wrapped arc
      // and every point is on the boundary.
      const auto points = sectionArcPoints(s, p, q, o, 0.1);
      EXPECT_NEAR(polylineLength(points), arc, 1e-9);
      double travelled = 0.0;
      for (const Vec2& x : points) {
        EXPECT_LT(distanceToBoundary(s, x), 1e-12);
        const double along = (x - p).norm() < 1e-12 ? 0.0 : sectionWrappedArc(s, p, x, o);
        EXPECT_GE(along, travelled - 1e-12);  // in order along the way
        EXPECT_LE(along, arc + 1e-12);
        travelled = along;
      }
    }
  }
  // A box from the bottom middle to the top middle.
  const Section box = boxSection(1.0, 0.5);
  EXPECT_NEAR(boundaryPosition(box, Vec2(0, -0.5)), 1.0, 1e-15);  // vertex 0 is (-1, -0.5)
  EXPECT_NEAR(sectionWrappedArc(box, Vec2(0, -0.5), Vec2(0, 0.5), 1), 3.0, 1e-15);
  const auto ccw = sectionArcPoints(box, Vec2(0, -0.5), Vec2(0, 0.5), 1, 0.1);
  const auto cw = sectionArcPoints(box, Vec2(0, -0.5), Vec2(0, 0.5), -1, 0.1);
  EXPECT_EQ(ccw, (std::vector<Vec2>{Vec2(0, -0.5), Vec2(1, -0.5), Vec2(1, 0.5), Vec2(0, 0.5)}));
  EXPECT_EQ(cw, (std::vector<Vec2>{Vec2(0, -0.5), Vec2(-1, -0.5), Vec2(-1, 0.5), Vec2(0, 0.5)}));
  // Starting on a vertex does not repeat it.
  EXPECT_EQ(sectionArcPoints(box, Vec2(1, -0.5), Vec2(1, 0.5), 1, 0.1),
            (std::vector<Vec2>{Vec2(1, -0.5), Vec2(1, 0.5)}));
}

TEST(SectionBoundary, CircleArcPointsStepAtMostTheGivenAngle) {
  const double r = 0.8, step = 0.05;
  const Section s = Section::circle(r);
  for (int o : {-1, 1}) {
    const Vec2 arrival = r * Vec2(std::cos(0.3), std::sin(0.3));
    const Vec2 departure = r * Vec2(std::cos(2.0), std::sin(2.0));
    const auto points = sectionArcPoints(s, arrival, departure, o, step);
    ASSERT_GE(points.size(), 2u);
    EXPECT_EQ(points.front(), arrival);
    EXPECT_EQ(points.back(), departure);
    double turned = 0.0;
    for (std::size_t i = 1; i < points.size(); ++i) {
      EXPECT_NEAR(points[i].norm(), r, 1e-12);
      const double angle =
          std::atan2(cross(points[i - 1], points[i]), points[i - 1].dot(points[i]));
      EXPECT_GT(o * angle, 0.0);
      EXPECT_LE(o * angle, step + 1e-12);
      turned += o * angle;
    }
    EXPECT_NEAR(turned * r, sectionWrappedArc(s, arrival, departure, o), 1e-12);
  }
  EXPECT_THROW(sectionArcPoints(s, Vec2(r, 0), Vec2(0, r), 1, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace reeve::test_section
