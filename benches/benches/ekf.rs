//! EKF predict, innovation (with the Cholesky factor of S), measurement score and update, for constant
//! velocity (dt = 1) and the SSA two-body model (dt = 60 s, three RK4 sub-steps), in f64 and f32.
//!
//! `cargo bench -p benches --bench ekf`
use benches::ssa_motion;
use criterion::{Criterion, criterion_group, criterion_main};
use nalgebra::{SMatrix, SVector};
use std::hint::black_box;
use tracker_core::ekf::{innovation, predict, update};
use tracker_core::{ConstantVelocity, Gaussian, MotionModel, PositionMeasurement, Real};

fn state<T: Real>(mean: [f64; 4], variances: [f64; 4]) -> Gaussian<T, 4> {
    Gaussian {
        mean: SVector::from(mean.map(T::of_f64)),
        covariance: SMatrix::from_diagonal(&SVector::from(variances.map(T::of_f64))),
    }
}

fn model<T: Real, M: MotionModel<T, 4>>(
    c: &mut Criterion,
    name: &str,
    motion: M,
    prior: Gaussian<T, 4>,
    dt: f64,
    offset: [f64; 2],
) {
    let measurement = PositionMeasurement::isotropic(T::of_f64(0.5));
    let dt = T::of_f64(dt);
    let predicted = predict(&motion, &prior, dt).expect("predict");
    let innov = innovation(&measurement, &predicted).expect("innovation");
    let z = SVector::from([predicted.mean[0] + T::of_f64(offset[0]), predicted.mean[1] + T::of_f64(offset[1])]);
    let mut group = c.benchmark_group(format!("ekf/{name}"));
    group.bench_function("predict", |b| b.iter(|| predict(black_box(&motion), black_box(&prior), black_box(dt))));
    group.bench_function("innovation", |b| b.iter(|| innovation(black_box(&measurement), black_box(&predicted))));
    group.bench_function("score", |b| b.iter(|| black_box(&innov).score(black_box(&z))));
    group.bench_function("update", |b| {
        b.iter(|| update(black_box(&measurement), black_box(&predicted), black_box(&innov), black_box(&z)))
    });
    group.finish();
}

fn ekf(c: &mut Criterion) {
    let cv = [0.0, 0.0, 1.0, 0.5];
    model::<f64, _>(
        c,
        "constant_velocity/f64",
        ConstantVelocity { acceleration_noise: 0.01 },
        state(cv, [1.0; 4]),
        1.0,
        [0.3, -0.2],
    );
    model::<f32, _>(
        c,
        "constant_velocity/f32",
        ConstantVelocity { acceleration_noise: 0.01 },
        state(cv, [1.0; 4]),
        1.0,
        [0.3, -0.2],
    );
    let look = 15f64.to_radians();
    let (r, v) = (7_000.0, (benches::EARTH_MU / 7_000.0f64).sqrt());
    let orbit = [r * look.cos(), r * look.sin(), -v * look.sin(), v * look.cos()];
    let variances = [1.0, 1.0, 4e-8, 4e-8];
    model::<f64, _>(c, "two_body/f64", ssa_motion::<f64>(), state(orbit, variances), 60.0, [0.4, -0.3]);
    model::<f32, _>(c, "two_body/f32", ssa_motion::<f32>(), state(orbit, variances), 60.0, [0.4, -0.3]);
}

criterion_group!(benches, ekf);
criterion_main!(benches);
