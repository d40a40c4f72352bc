//! rustfft's planners for `f32` and `f64`, behind functions that are not generic.
//!
//! A planner's algorithms (rustfft's butterflies for every SIMD flavour) are generic code: they
//! are compiled in whichever crate names the float type. Named here, they are compiled once,
//! and the core's library, its unit-test build and everything linked with them share that
//! code instead of each compiling its own copy. Plans come back as `Arc<dyn Fft<T>>`, as from
//! rustfft's own planner, so calling them costs what it did.
//!
//! Natively the planner picks AVX, SSE or scalar algorithms at run time. In WASM (always built
//! with `simd128`) it is the WASM SIMD planner alone, so the scalar algorithms stay out of the
//! module.

use std::sync::Arc;

use rustfft::{Fft, FftDirection, FftNum};

#[cfg(not(target_arch = "wasm32"))]
type Inner<T> = rustfft::FftPlanner<T>;
#[cfg(target_arch = "wasm32")]
type Inner<T> = rustfft::FftPlannerWasmSimd<T>;

#[cfg(not(target_arch = "wasm32"))]
fn inner<T: FftNum>() -> Inner<T> {
    rustfft::FftPlanner::new()
}

#[cfg(target_arch = "wasm32")]
fn inner<T: FftNum>() -> Inner<T> {
    rustfft::FftPlannerWasmSimd::new().expect("the WASM build enables simd128")
}

macro_rules! planner {
    ($name:ident, $t:ty) => {
        /// A planner of transforms of this float type; it keeps the plans it has made, so
        /// planning a length again is a look-up.
        pub struct $name(Inner<$t>);

        impl $name {
            /// A planner with no plans yet.
            #[allow(clippy::new_without_default)]
            pub fn new() -> Self {
                Self(inner())
            }

            /// The plan of the transform of length `len` in `direction` (unnormalised, as
            /// rustfft's transforms are).
            pub fn plan_fft(&mut self, len: usize, direction: FftDirection) -> Arc<dyn Fft<$t>> {
                self.0.plan_fft(len, direction)
            }

            /// The forward transform of length `len`: X_k = Σ_j x_j e^{−2πijk/len}.
            pub fn plan_fft_forward(&mut self, len: usize) -> Arc<dyn Fft<$t>> {
                self.0.plan_fft_forward(len)
            }

            /// The inverse transform of length `len`: x_j = Σ_k X_k e^{+2πijk/len}.
            pub fn plan_fft_inverse(&mut self, len: usize) -> Arc<dyn Fft<$t>> {
                self.0.plan_fft_inverse(len)
            }
        }
    };
}

planner!(Planner32, f32);
planner!(Planner64, f64);
