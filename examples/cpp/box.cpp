// depo from C++: the box solver with std::vector arrays and the RAII layer of depo.hpp;
// particles of 35 to 140 um, each with its own capture velocity.
// From the repository root, after the one release build (README), linked statically:
//   c++ -std=c++17 -I crates/capi/include examples/cpp/box.cpp target/release/libdepo.a -lpthread -ldl -o box && ./box [N]
// or after `crates/capi/install.sh $HOME/.local`, with PKG_CONFIG_PATH=$HOME/.local/lib/pkgconfig:
//   c++ -std=c++17 examples/cpp/box.cpp $(pkg-config --cflags --libs depo) -o box
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "depo.hpp"

namespace {

struct Particles {
    std::array<std::vector<double>, 3> x, v;
    std::vector<double> vc;  // capture velocity of each particle, from its diameter
    std::size_t size() const { return x[0].size(); }
};

double uniform(std::uint64_t &state) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) / 9007199254740992.0;
}

}  // namespace

int main(int argc, char **argv) {
    const std::size_t injected = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 20000;
    std::printf("depo %s\n", depo::version().c_str());
    try {
        depo::WallLaw::preset("granite");
        return 1;
    } catch (const depo::Error &e) {
        std::printf("rejected: %s\n", e.what());
    }
    DepoLawParams params = depo::WallLaw::preset("sim-70um").params();
    params.mu = 0.3;
    const depo::WallLaw law(params);

    Particles p;
    std::uint64_t seed = 7;
    for (int a = 0; a < 3; a++) {
        p.x[a].resize(injected);
        p.v[a].resize(injected);
    }
    std::vector<double> diameter(injected);
    for (std::size_t i = 0; i < injected; i++) {
        for (int a = 0; a < 3; a++) {
            p.x[a][i] = 0.05 + 0.9 * uniform(seed);
            p.v[a][i] = (uniform(seed) - 0.5) * 4.0 * uniform(seed);
        }
        diameter[i] = 35e-6 + 105e-6 * uniform(seed);
    }
    p.vc.resize(injected);
    law.capture_velocities(70e-6, 1.51, injected, diameter.data(), p.vc.data());  // paper Fig. 8

    DepoTally tally{};
    std::size_t deposited = 0;
    std::array<std::vector<double>, 3> hv, hn;
    std::vector<double> hvc;
    std::vector<std::size_t> index;
    std::vector<std::uint8_t> outcome;
    const double dt = 1e-3, gravity = -9.81;
    for (int step = 0; step < 2000; step++) {
        for (auto &c : hv) c.clear();
        for (auto &c : hn) c.clear();
        hvc.clear();
        index.clear();
        for (std::size_t i = 0; i < p.size(); i++) {
            p.v[2][i] += gravity * dt;
            int wall = -1;
            double sign = 0.0;
            for (int a = 0; a < 3; a++) {
                double x = p.x[a][i] + p.v[a][i] * dt;
                if (x < 0.0 || x > 1.0) {
                    if (wall < 0) {
                        wall = a;
                        sign = x < 0.0 ? 1.0 : -1.0;
                    }
                    x = x < 0.0 ? -x : 2.0 - x;
                }
                p.x[a][i] = x;
            }
            if (wall >= 0) {
                index.push_back(i);
                for (int a = 0; a < 3; a++) {
                    hv[a].push_back(p.v[a][i]);
                    hn[a].push_back(a == wall ? sign : 0.0);
                }
                hvc.push_back(p.vc[i]);
            }
        }
        outcome.resize(index.size());
        DepoImpactsF64 batch{};
        batch.n = index.size();
        batch.vx = hv[0].data();
        batch.vy = hv[1].data();
        batch.vz = hv[2].data();
        batch.nx = hn[0].data();
        batch.ny = hn[1].data();
        batch.nz = hn[2].data();
        batch.outcome = outcome.data();
        law.apply(batch, hvc.data(), &tally);

        std::vector<bool> gone(p.size(), false);
        for (std::size_t k = 0; k < index.size(); k++) {
            if (outcome[k] == DEPO_CAPTURED) {
                gone[index[k]] = true;
                deposited++;
            } else {
                for (int a = 0; a < 3; a++) p.v[a][index[k]] = hv[a][k];
            }
        }
        std::size_t kept = 0;
        for (std::size_t i = 0; i < p.size(); i++) {
            if (gone[i]) continue;
            for (int a = 0; a < 3; a++) {
                p.x[a][kept] = p.x[a][i];
                p.v[a][kept] = p.v[a][i];
            }
            p.vc[kept] = p.vc[i];
            kept++;
        }
        for (int a = 0; a < 3; a++) {
            p.x[a].resize(kept);
            p.v[a].resize(kept);
        }
        p.vc.resize(kept);
    }
    std::printf("injected %zu airborne %zu deposited %zu\n", injected, p.size(), deposited);
    std::printf("tally rebound %llu captured %llu skipped %llu invalid %llu\n",
                static_cast<unsigned long long>(tally.rebound), static_cast<unsigned long long>(tally.captured),
                static_cast<unsigned long long>(tally.skipped), static_cast<unsigned long long>(tally.invalid));
    return p.size() + deposited == injected && tally.captured == deposited ? 0 : 1;
}
