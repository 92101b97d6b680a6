// depo.hpp: a header-only C++11 layer over depo.h. Owners free what they hold (RAII), a
// failing call throws depo::Error with the library's message, and batches stay views of the
// caller's arrays.
#ifndef DEPO_HPP
#define DEPO_HPP

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "depo.h"

namespace depo {

/// A failed depo call: the status code and depo_last_error()'s message.
class Error : public std::runtime_error {
  public:
    Error(std::int32_t status, const char *message) : std::runtime_error(message), status_(status) {}
    std::int32_t status() const noexcept { return status_; }

  private:
    std::int32_t status_;
};

/// Throws depo::Error unless status is DEPO_OK.
inline void check(std::int32_t status) {
    if (status != DEPO_OK) throw Error(status, depo_last_error());
}

/// The library's version, "MAJOR.MINOR.PATCH".
inline std::string version() { return depo_version(); }

/// Threads for large batches (0: one per core; 1: only the calling thread, for OpenMP and MPI
/// hosts; at most DEPO_MAX_THREADS). Batches below DEPO_PARALLEL_MIN always run on the caller.
inline void set_num_threads(std::size_t threads) { check(depo_set_num_threads(threads)); }

/// The deposition velocity (m/s) of each of `n` particles in wall cells from a deposition
/// correlation (DEPO_CORRELATION_*; depo_deposition_velocity: the arrays and units are in
/// depo.h). Throws depo::Error on bad inputs, writing nothing.
inline void deposition_velocity(std::int32_t correlation, std::int32_t orientation, const DepoAir& air,
                                double gravity, std::size_t n, const double* friction_velocity,
                                const double* diameter, const double* density, double* velocity) {
    check(depo_deposition_velocity(correlation, orientation, &air, gravity, n, friction_velocity, diameter, density,
                                   velocity));
}

/// The chance that each of `n` particles in wall cells reaches the wall within a step `dt`
/// (s), from a deposition correlation (depo_wall_function_probability: the arrays, units and
/// how a solver uses the chance are in depo.h). Throws depo::Error on bad inputs, writing
/// nothing.
inline void wall_function_probability(std::int32_t correlation, std::int32_t orientation, const DepoAir& air,
                                      double gravity, double dt, std::size_t n, const double* friction_velocity,
                                      const double* layer, const double* diameter, const double* density,
                                      double* probability) {
    check(depo_wall_function_probability(correlation, orientation, &air, gravity, dt, n, friction_velocity, layer,
                                         diameter, density, probability));
}

/// An owned wall law; move-only.
class WallLaw {
  public:
    explicit WallLaw(const DepoLawParams &params) { check(depo_law_new(&params, &law_)); }
    /// The law of a preset of the paper's Table 1, e.g. "li1997-sio2".
    static WallLaw preset(const std::string &id) {
        WallLaw law;
        check(depo_law_preset(id.c_str(), &law.law_));
        return law;
    }
    ~WallLaw() { depo_law_free(law_); }
    WallLaw(WallLaw &&other) noexcept : law_(other.law_) { other.law_ = nullptr; }
    WallLaw &operator=(WallLaw &&other) noexcept {
        if (this != &other) {
            depo_law_free(law_);
            law_ = other.law_;
            other.law_ = nullptr;
        }
        return *this;
    }
    WallLaw(const WallLaw &) = delete;
    WallLaw &operator=(const WallLaw &) = delete;

    /// A copy of this law that treats captured particles by `mode`: DEPO_CAPTURE_DEPOSIT or
    /// DEPO_CAPTURE_KEEP_ON_WALL (only the normal velocity zeroed; outcome DEPO_CAPTURED).
    WallLaw with_capture_mode(int32_t mode) const {
        WallLaw law;
        check(depo_law_with_capture_mode(law_, mode, &law.law_));
        return law;
    }
    DepoLawParams params() const {
        DepoLawParams p{};
        check(depo_law_params(law_, &p));
        return p;
    }
    /// Applies the law to a batch in place; adds to *tally when given.
    void apply(DepoImpactsF64 &batch, DepoTally *tally = nullptr) const { check(depo_apply_f64(law_, &batch, tally)); }
    void apply(DepoImpactsF32 &batch, DepoTally *tally = nullptr) const { check(depo_apply_f32(law_, &batch, tally)); }
    /// Applies the law with one capture velocity per particle (a polydisperse batch).
    void apply(DepoImpactsF64 &batch, const double *capture_velocity, DepoTally *tally = nullptr) const {
        check(depo_apply_sized_f64(law_, &batch, capture_velocity, tally));
    }
    void apply(DepoImpactsF32 &batch, const float *capture_velocity, DepoTally *tally = nullptr) const {
        check(depo_apply_sized_f32(law_, &batch, capture_velocity, tally));
    }
    /// Capture velocities (m/s) from diameters (m): vc (d / reference_diameter)^-exponent.
    void capture_velocities(double reference_diameter, double exponent, std::size_t n, const double *diameter,
                            double *capture_velocity) const {
        check(depo_capture_velocities(law_, reference_diameter, exponent, n, diameter, capture_velocity));
    }
    const DepoWallLaw *get() const noexcept { return law_; }

  private:
    WallLaw() = default;
    DepoWallLaw *law_ = nullptr;
};

}  // namespace depo

#endif  // DEPO_HPP
