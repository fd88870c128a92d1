#pragma once
// Broadband identification on a measured rotor phase. Internal to ltp::htf (identify.cc calls
// it once the excited lines and the input's amplitudes are known).
#include <Eigen/Dense>
#include <vector>

#include "ltp/htf/identify.h"

namespace ltp::internal {

/// Broadband records whose system phase θ_r(t) is measured (a tacho or an encoder): the speed
/// may differ from 2π/T and drift, so the response lines ω_k + zθ' leave the DFT's bins, and
/// the per-bin regression of the constant-speed route does not apply. One least-squares fit
/// over all records stacked instead:
///   y_r(t) = c + Σ_{k,z} (H_z(ω_k) U_rk e^{j(ω_k t + z θ_r(t))} + c.c.) + noise,
/// U_rk the input's measured amplitude of e^{jω_k t} in record r (absolute time). The records'
/// differing U_rk separate the orders as the constant-speed route does line by line; the
/// residual gives the output noise, σ²(XᵀX)⁻¹ its part of each bound. The input's noise does
/// not show in that residual (the fit absorbs it into H), so it is propagated to first order:
/// an error δU_rk (circular, of variance `input_bin_variance`, the input's power per unexcited
/// bin) changes the model by 2 Re(δU_rk Σ_z H_z(ω_k) e^{j(ω_k t + zθ_r)}) in record r, and the
/// fit's linear response to that change is the estimates' error.
/// @throws InputError when the fit would be too large to hold (lines × orders × samples).
IdentifyResult IdentifyBroadbandOnAngle(const TimeData& data, const IdentifyOptions& options,
                                        const std::vector<double>& omegas,
                                        const Eigen::MatrixXcd& input_amplitudes,
                                        double input_bin_variance);

}  // namespace ltp::internal
