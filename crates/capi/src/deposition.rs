//! The host's deposition map: deposited count and mass per wall face.

use super::{check_disjoint, set_last_error, slice, slice_mut, span, Failure, DEPO_CAPTURED, DEPO_ERR_PANIC, DEPO_OK};
use std::panic::{catch_unwind, AssertUnwindSafe};

/// Adds the particles that a `depo_apply_*` call captured to a deposition map: for every `i`
/// with `outcome[i] == DEPO_CAPTURED`, `count[face[i]] += 1` and, when `mass` and
/// `deposited_mass` are both given, `deposited_mass[face[i]] += mass[i]` (kg).
///
/// `face` holds the host's face ids, `0 <= face[i] < nfaces` for every captured particle (other
/// particles' ids are not read); `count` and `deposited_mass` have `nfaces` entries. A face id
/// out of range, or `count` or `deposited_mass` overlapping another array, is
/// `DEPO_ERR_INVALID` and changes nothing. One pass over the batch, outside the
/// law's kernel, so a host that wants no map pays nothing.
#[no_mangle]
pub unsafe extern "C" fn depo_accumulate_deposits(
    n: usize,
    outcome: *const u8,
    face: *const i64,
    mass: *const f64,
    nfaces: usize,
    count: *mut u64,
    deposited_mass: *mut f64,
) -> i32 {
    ffi_guard!({
        let outcome = slice(outcome, n, "outcome")?;
        let face = slice(face, n, "face")?;
        let count = slice_mut(count, nfaces, "count")?;
        let masses = match (mass.is_null(), deposited_mass.is_null()) {
            (false, false) => Some((slice(mass, n, "mass")?, slice_mut(deposited_mass, nfaces, "deposited_mass")?)),
            _ => None,
        };
        let mut arrays = vec![("outcome", span(outcome)), ("face", span(face)), ("count", span(count))];
        if let Some((mass, deposited)) = &masses {
            arrays.extend([("mass", span(mass)), ("deposited_mass", span(deposited))]);
        }
        check_disjoint(&arrays)?;
        let captured = || (0..n).filter(|&i| outcome[i] == DEPO_CAPTURED);
        if let Some(i) = captured().find(|&i| face[i] < 0 || face[i] as u64 >= nfaces as u64) {
            return Err(Failure::invalid(format!("face[{i}] = {} is outside 0..{nfaces}", face[i])));
        }
        match masses {
            Some((mass, deposited)) => {
                for i in captured() {
                    count[face[i] as usize] += 1;
                    deposited[face[i] as usize] += mass[i];
                }
            }
            None => {
                for i in captured() {
                    count[face[i] as usize] += 1;
                }
            }
        }
        Ok(())
    })
}
