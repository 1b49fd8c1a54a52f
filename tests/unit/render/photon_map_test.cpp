#include <gtest/gtest.h>

#include "base/rng.h"
#include "render/photon_map.h"

using namespace dp;

namespace {
std::vector<Photon> random_photons(size_t n, uint64_t seed) {
    Rng rng(seed, 3);
    std::vector<Photon> ps(n);
    for (Photon& p : ps) {
        p.position = vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - 1.0f;
        p.flux = vec3(rng.uniform() - 0.5f, rng.uniform(), -rng.uniform());
        p.normal = rng.uniform() < 0.8f ? vec3(0, 1, 0) : vec3(0, -1, 0);
    }
    return ps;
}
/// Reference: sum over every photon within r of x on an upward-facing surface.
dvec3 brute_gather(const std::vector<Photon>& ps, const vec3& x, float r) {
    dvec3 sum(0);
    for (const Photon& p : ps)
        if (glm::dot(p.position - x, p.position - x) <= r * r && p.normal.y > 0) sum += dvec3(p.flux);
    return sum;
}

void expect_near(const dvec3& got, const dvec3& want) {
    EXPECT_NEAR(got.x, want.x, 1e-9);
    EXPECT_NEAR(got.y, want.y, 1e-9);
    EXPECT_NEAR(got.z, want.z, 1e-9);
}

}  // namespace

TEST(PhotonMap, GatherEqualsABruteForceSumOverPhotonsInRangeFacingTheSameWay) {
    std::vector<Photon> ps = random_photons(20000, 1);
    for (float r : {0.01f, 0.07f, 0.3f}) {
        PhotonMap map;
        map.build(ps, r);
        Rng rng(9, 9);
        for (int q = 0; q < 200; ++q) {
            vec3 x = vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.4f - 1.2f;
            expect_near(map.gather(x, vec3(0, 1, 0)), brute_gather(ps, x, r));
        }
    }
}

TEST(PhotonMap, ReachesIsTrueNearEveryPhotonAndFalseFarFromAll) {
    std::vector<Photon> ps = random_photons(500, 2);
    PhotonMap map;
    map.build(ps, 0.01f);
    for (const Photon& p : ps) EXPECT_TRUE(map.reaches(p.position + vec3(0.005f)));
    EXPECT_FALSE(PhotonMap().reaches(vec3(0)));
    // Cells are looked up by their exact key: far from every photon the answer is no.
    for (int i = 0; i < 100; ++i) EXPECT_FALSE(map.reaches(vec3(50.0f + i, 50.0f, 50.0f)));
    EXPECT_FALSE(map.reaches(vec3(0, 0, 1.2f)));
}

TEST(PhotonMap, SignedFluxCancelsExactlyInDouble) {
    std::vector<Photon> ps;
    for (int i = 0; i < 100000; ++i) {
        ps.push_back({vec3(0), vec3(1e6f + i), vec3(0, 1, 0)});
        ps.push_back({vec3(0), -vec3(1e6f + i), vec3(0, 1, 0)});
    }
    PhotonMap map;
    map.build(ps, 0.1f);
    EXPECT_EQ(map.gather(vec3(0), vec3(0, 1, 0)), dvec3(0));
}

TEST(PhotonMap, GatherStaysExactWhenPhotonsSpanMoreCellsThanOneKeyHolds) {
    // 1e-4 radius over +-1000 units: ~1e7 cells per axis, beyond 63 bits of exact offsets.
    std::vector<Photon> ps = random_photons(3000, 4);
    for (size_t i = 0; i < ps.size(); ++i) ps[i].position *= (i % 2 ? 1000.0f : 1e-3f);
    const float r = 1e-4f;
    PhotonMap map;
    map.build(ps, r);
    for (size_t q = 0; q < ps.size(); q += 7) {
        vec3 x = ps[q].position + vec3(3e-5f);
        expect_near(map.gather(x, vec3(0, 1, 0)), brute_gather(ps, x, r));
        EXPECT_TRUE(map.reaches(x));
    }
}
