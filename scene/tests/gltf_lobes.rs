//! The glTF material extensions' lobes (specular, anisotropy, clearcoat, sheen): white
//! furnace, chi-square of sampling against the density, and what each factor changes.

use glam::{Vec2, Vec3};
use prism_sampling::stream::{IndependentStream, SampleStream};
use prism_scene::bsdf::{CoatingAlbedo, MetallicRoughness, Specular};
use prism_spectrum::SampledSpectrum;
use std::sync::LazyLock;

#[path = "support/albedo.rs"]
mod albedo;
#[path = "support/chi_square.rs"]
mod chi_square;
use albedo::{albedo, split};
use chi_square::chi_square_directions;

static COATING: LazyLock<CoatingAlbedo> = LazyLock::new(|| CoatingAlbedo::new(1.5));

fn outgoing() -> [Vec3; 3] {
    [
        Vec3::Z,
        Vec3::new(0.6, 0.3, 0.74).normalize(),
        Vec3::new(0.95, 0.0, 0.1f32.sqrt()).normalize(),
    ]
}

fn reciprocal(f: impl Fn(Vec3, Vec3) -> SampledSpectrum<4>) {
    let mut stream = IndependentStream::new(67, 0, 0);
    for _ in 0..2000 {
        let wo = prism_sampling::warp::cosine_hemisphere(stream.next_2d());
        let wi = prism_sampling::warp::cosine_hemisphere(stream.next_2d());
        let (x, y) = (f(wo, wi), f(wi, wo));
        for k in 0..4 {
            assert!(
                (x[k] - y[k]).abs() <= 1e-4 * x[k].abs().max(1.0),
                "{wo} {wi}: {x:?} vs {y:?}"
            );
        }
    }
}

mod specular {
    use super::*;

    fn white(roughness: f32, weight: f32, color: [f32; 4]) -> MetallicRoughness<'static, 4> {
        MetallicRoughness::new(SampledSpectrum([1.0; 4]), 0.0, roughness, &COATING).with_specular(
            Specular {
                weight,
                color: SampledSpectrum(color),
            },
        )
    }

    /// White furnace: whatever the specular strength and colour (including colours above
    /// 1, which Blender writes for a specular level above 0.5), a white base reflects
    /// everything: the coating's albedo is exact, so the diffuse base takes the rest.
    #[test]
    fn a_white_base_reflects_everything() {
        for roughness in [0.1f32, 0.5, 0.9] {
            for (weight, color) in [
                (1.0f32, [1.0f32; 4]),
                (0.5, [1.0, 0.5, 0.0, 2.0]),
                (1.0, [2.0, 5.0, 0.2, 1.0]),
                (0.0, [1.0; 4]),
            ] {
                for wo in outgoing() {
                    let bsdf = white(roughness, weight, color);
                    for (k, a) in albedo(|w, uc, u| bsdf.sample(w, uc, u), wo)
                        .into_iter()
                        .enumerate()
                    {
                        assert!(
                            (a - 1.0).abs() < 8e-3,
                            "roughness {roughness}, weight {weight}, colour {color:?}, wo {wo}, lane {k}: {a}"
                        );
                    }
                }
            }
        }
    }

    /// The extension's end points: at normal incidence the coating reflects F0 times the
    /// colour times the weight, at grazing the weight; weight 0 leaves a Lambertian
    /// surface exactly; colour and weight 1 are the bare material.
    #[test]
    fn factors_set_the_reflectance_at_both_ends() {
        let black = |weight: f32, color: f32| {
            MetallicRoughness::new(SampledSpectrum([0.0; 4]), 0.0, 0.05, &COATING).with_specular(
                Specular {
                    weight,
                    color: SampledSpectrum([color; 4]),
                },
            )
        };
        let bare = MetallicRoughness::new(SampledSpectrum([0.0; 4]), 0.0, 0.05, &COATING);
        let wo = Vec3::new(0.01, 0.0, 1.0).normalize();
        let wi = Vec3::new(-0.01, 0.0, 1.0).normalize();
        let normal = bare.f(wo, wi)[0];
        let ratio = |weight, color| black(weight, color).f(wo, wi)[0] / normal;
        assert!((ratio(1.0, 1.0) - 1.0).abs() < 1e-5);
        assert!((ratio(0.5, 1.0) - 0.5).abs() < 1e-3, "{}", ratio(0.5, 1.0));
        assert!((ratio(1.0, 2.0) - 2.0).abs() < 1e-3, "{}", ratio(1.0, 2.0));
        assert!((ratio(1.0, 0.0)).abs() < 1e-6);
        // Weight 0: only the base, as Lambert.
        let matte = MetallicRoughness::new(SampledSpectrum([0.6; 4]), 0.0, 0.5, &COATING)
            .with_specular(Specular {
                weight: 0.0,
                color: SampledSpectrum([1.0; 4]),
            });
        let (a, b) = (
            Vec3::new(0.3, 0.1, 0.9).normalize(),
            Vec3::new(-0.5, 0.2, 0.8).normalize(),
        );
        assert!((matte.f(a, b)[0] - 0.6 / std::f32::consts::PI).abs() < 1e-5);
        // Grazing: the weight, whatever the colour.
        let g_o = Vec3::new(0.999, 0.0, 0.045).normalize();
        let g_i = Vec3::new(-0.999, 0.0, 0.045).normalize();
        let grazing = |weight, color| black(weight, color).f(g_o, g_i)[0] / bare.f(g_o, g_i)[0];
        assert!(
            (grazing(0.5, 0.0) - grazing(0.5, 1.0)).abs() < 0.1,
            "{} {}",
            grazing(0.5, 0.0),
            grazing(0.5, 1.0)
        );
    }

    #[test]
    fn sampling_matches_its_density_and_is_reciprocal() {
        let bsdf =
            MetallicRoughness::new(SampledSpectrum([0.8, 0.5, 0.3, 0.1]), 0.2, 0.4, &COATING)
                .with_specular(Specular {
                    weight: 0.7,
                    color: SampledSpectrum([1.5, 0.5, 1.0, 3.0]),
                });
        let wo = Vec3::new(0.5, 0.2, 0.84).normalize();
        chi_square_directions(
            "specular",
            |u| {
                let (uc, u) = split(u);
                bsdf.sample(wo, uc, u).map(|s| s.wi)
            },
            |wi| f64::from(bsdf.pdf(wo, wi)),
        );
        reciprocal(|a, b| bsdf.f(a, b));
    }
}

mod anisotropy {
    use super::*;

    fn brushed(strength: f32, angle: f32, metallic: f32) -> MetallicRoughness<'static, 4> {
        MetallicRoughness::new(
            SampledSpectrum([0.9, 0.7, 0.5, 1.0]),
            metallic,
            0.3,
            &COATING,
        )
        .with_anisotropy(strength, Vec2::new(angle.cos(), angle.sin()))
    }

    #[test]
    fn sampling_matches_its_density_and_is_reciprocal() {
        for (strength, angle, metallic) in
            [(0.8f32, 0.0f32, 1.0f32), (0.6, 1.0, 0.5), (1.0, -2.0, 0.0)]
        {
            let bsdf = brushed(strength, angle, metallic);
            for (k, wo) in [
                Vec3::new(0.5, 0.2, 0.84).normalize(),
                Vec3::new(-0.1, 0.8, 0.6).normalize(),
            ]
            .into_iter()
            .enumerate()
            {
                chi_square_directions(
                    &format!("anisotropic {strength} {angle} {metallic} wo {k}"),
                    |u| {
                        let (uc, u) = split(u);
                        bsdf.sample(wo, uc, u).map(|s| s.wi)
                    },
                    |wi| f64::from(bsdf.pdf(wo, wi)),
                );
            }
            reciprocal(|a, b| bsdf.f(a, b));
        }
    }

    /// The highlight stretches along the direction: reflecting a light from along the
    /// direction and from across it at the same angle off the mirror direction differ, and
    /// turning the direction by 90 degrees swaps them; strength 0 is isotropic exactly.
    #[test]
    fn the_highlight_stretches_along_the_direction() {
        let wo = Vec3::Z;
        let off = |azimuth: f32| {
            let t: f32 = 0.5;
            Vec3::new(t.sin() * azimuth.cos(), t.sin() * azimuth.sin(), t.cos())
        };
        let along = brushed(0.9, 0.0, 1.0);
        let across = brushed(0.9, std::f32::consts::FRAC_PI_2, 1.0);
        let (x, y) = (
            along.f(wo, off(0.0))[0],
            along.f(wo, off(std::f32::consts::FRAC_PI_2))[0],
        );
        assert!(x > 3.0 * y, "along {x} across {y}");
        let (x2, y2) = (
            across.f(wo, off(0.0))[0],
            across.f(wo, off(std::f32::consts::FRAC_PI_2))[0],
        );
        assert!(
            (x - y2).abs() < 1e-4 * x && (y - x2).abs() < 1e-4 * x,
            "{x} {y} {x2} {y2}"
        );
        let none = brushed(0.0, 1.0, 1.0);
        let iso = MetallicRoughness::new(SampledSpectrum([0.9, 0.7, 0.5, 1.0]), 1.0, 0.3, &COATING);
        assert_eq!(none.f(wo, off(0.3)).0, iso.f(wo, off(0.3)).0);
    }

    /// White furnace: a white dielectric base reflects within 3% of everything (the
    /// coating's albedo is read at the root-mean-square roughness: an estimate for a
    /// stretched lobe), a white metal never more than everything.
    #[test]
    fn energy_is_nearly_conserved() {
        for strength in [0.5f32, 1.0] {
            for wo in outgoing() {
                let white = MetallicRoughness::new(SampledSpectrum([1.0; 4]), 0.0, 0.3, &COATING)
                    .with_anisotropy(strength, Vec2::new(0.6, 0.8));
                let a = albedo(|w, uc, u| white.sample(w, uc, u), wo)[0];
                assert!((a - 1.0).abs() < 0.03, "strength {strength}, wo {wo}: {a}");
                let metal = MetallicRoughness::new(SampledSpectrum([1.0; 4]), 1.0, 0.3, &COATING)
                    .with_anisotropy(strength, Vec2::new(0.6, 0.8));
                let m = albedo(|w, uc, u| metal.sample(w, uc, u), wo)[0];
                assert!(
                    m <= 1.0 + 3e-3 && m > 0.3,
                    "metal, strength {strength}, wo {wo}: {m}"
                );
            }
        }
    }
}

mod layers {
    use super::*;
    use prism_scene::bsdf::{Clearcoat, Layered, Sheen, TransportMode};

    fn layered(
        base: MetallicRoughness<'static, 4>,
        sheen: Option<Sheen<4>>,
        clearcoat: Option<Clearcoat>,
    ) -> Layered<'static, 4> {
        Layered {
            base,
            sheen,
            clearcoat,
            mode: TransportMode::Radiance,
        }
    }

    fn white(metallic: f32, roughness: f32) -> MetallicRoughness<'static, 4> {
        MetallicRoughness::new(SampledSpectrum([1.0; 4]), metallic, roughness, &COATING)
    }

    /// White furnace: a white sheen and a clear coat, alone or together, over a white
    /// dielectric base reflect everything (each layer takes from those below what it
    /// reflects), at every roughness and angle, including a coat tilted by its own normal.
    #[test]
    fn white_layers_over_a_white_base_reflect_everything() {
        let tilted = Vec3::new(0.3, -0.2, 1.0).normalize();
        for (k, (sheen, coat)) in [
            (Some(Sheen::new(SampledSpectrum([1.0; 4]), 0.3)), None),
            (Some(Sheen::new(SampledSpectrum([1.0; 4]), 0.9)), None),
            (
                Some(Sheen::new(SampledSpectrum([1.0, 0.5, 0.2, 0.0]), 0.07)),
                None,
            ),
            (None, Some(Clearcoat::new(1.0, 0.0, None))),
            (None, Some(Clearcoat::new(0.7, 0.4, None))),
            (None, Some(Clearcoat::new(1.0, 0.2, Some(tilted)))),
            (
                Some(Sheen::new(SampledSpectrum([0.8; 4]), 0.5)),
                Some(Clearcoat::new(1.0, 0.1, None)),
            ),
        ]
        .into_iter()
        .enumerate()
        {
            for roughness in [0.3f32, 0.8] {
                for wo in outgoing() {
                    let bsdf = layered(white(0.0, roughness), sheen, coat);
                    for (lane, a) in albedo(|w, uc, u| bsdf.sample(w, uc, u), wo)
                        .into_iter()
                        .enumerate()
                    {
                        assert!(
                            (a - 1.0).abs() < 0.015,
                            "case {k}, roughness {roughness}, wo {wo}, lane {lane}: {a}"
                        );
                    }
                }
            }
        }
    }

    /// Each layer shows: the coat adds a sharp highlight over a rough black base, the
    /// sheen adds grazing back-scatter; factor 0 (or a black sheen) is the base exactly.
    #[test]
    fn each_layer_changes_the_reflection_and_zero_removes_it() {
        let black = MetallicRoughness::new(SampledSpectrum([0.1; 4]), 0.0, 0.9, &COATING);
        let wo = Vec3::new(0.5, 0.0, 0.866);
        let mirror = Vec3::new(-0.5, 0.0, 0.866);
        let bare = layered(black.clone(), None, None).f(wo, mirror)[0];
        let coated =
            layered(black.clone(), None, Some(Clearcoat::new(1.0, 0.05, None))).f(wo, mirror)[0];
        assert!(coated > 10.0 * bare, "coat {coated} vs bare {bare}");
        let grazing_o = Vec3::new(0.97, 0.0, 0.243);
        let back = Vec3::new(0.9, 0.2, 0.39).normalize();
        let plain = layered(black.clone(), None, None).f(grazing_o, back)[0];
        let velvet = layered(
            black.clone(),
            Some(Sheen::new(SampledSpectrum([1.0; 4]), 0.3)),
            None,
        )
        .f(grazing_o, back)[0];
        assert!(velvet > 2.0 * plain, "sheen {velvet} vs plain {plain}");
        for (sheen, coat) in [
            (Some(Sheen::new(SampledSpectrum([0.0; 4]), 0.5)), None),
            (None, Some(Clearcoat::new(0.0, 0.5, None))),
        ] {
            assert_eq!(
                layered(black.clone(), sheen, coat).f(wo, back).0,
                black.f(wo, back).0
            );
        }
    }

    #[test]
    fn sampling_matches_its_density() {
        let base =
            MetallicRoughness::new(SampledSpectrum([0.8, 0.5, 0.3, 0.1]), 0.3, 0.6, &COATING);
        let tilted = Vec3::new(-0.2, 0.3, 1.0).normalize();
        for (k, bsdf) in [
            layered(
                base.clone(),
                Some(Sheen::new(SampledSpectrum([0.9, 0.6, 0.3, 0.1]), 0.4)),
                None,
            ),
            layered(
                base.clone(),
                None,
                Some(Clearcoat::new(0.8, 0.3, Some(tilted))),
            ),
            layered(
                base.clone(),
                Some(Sheen::new(SampledSpectrum([1.0; 4]), 0.2)),
                Some(Clearcoat::new(1.0, 0.2, None)),
            ),
        ]
        .into_iter()
        .enumerate()
        {
            for (j, wo) in [
                Vec3::new(0.5, 0.2, 0.84).normalize(),
                Vec3::new(0.1, -0.9, -0.4).normalize(),
            ]
            .into_iter()
            .enumerate()
            {
                chi_square_directions(
                    &format!("layered {k} wo {j}"),
                    |u| {
                        let (uc, u) = split(u);
                        bsdf.sample(wo, uc, u).map(|s| s.wi)
                    },
                    |wi| f64::from(bsdf.pdf(wo, wi)),
                );
            }
        }
    }

    /// Light paths see the adjoint: the BSDF for importance is the radiance one with its
    /// arguments swapped (the layers scale by the camera side's albedo on both).
    #[test]
    fn importance_transport_is_the_adjoint() {
        let base =
            MetallicRoughness::new(SampledSpectrum([0.8, 0.5, 0.3, 0.1]), 0.3, 0.6, &COATING);
        let radiance = layered(
            base,
            Some(Sheen::new(SampledSpectrum([0.9, 0.6, 0.3, 0.1]), 0.4)),
            Some(Clearcoat::new(0.8, 0.3, None)),
        );
        let importance = Layered {
            mode: TransportMode::Importance,
            ..radiance.clone()
        };
        let mut stream = IndependentStream::new(71, 0, 0);
        for _ in 0..500 {
            let wo = prism_sampling::warp::cosine_hemisphere(stream.next_2d());
            let wi = prism_sampling::warp::cosine_hemisphere(stream.next_2d());
            let (a, b) = (radiance.f(wo, wi), importance.f(wi, wo));
            for k in 0..4 {
                assert!((a[k] - b[k]).abs() <= 1e-5 * a[k].max(1.0), "{a:?} {b:?}");
            }
        }
    }

    /// No NaN or infinity from any direction, including grazing, below the surface, and
    /// degenerate inputs.
    #[test]
    fn finite_everywhere() {
        let base = MetallicRoughness::new(SampledSpectrum([1.0; 4]), 0.5, 0.0, &COATING);
        let bsdf = layered(
            base,
            Some(Sheen::new(SampledSpectrum([1.0; 4]), 0.0)),
            Some(Clearcoat::new(1.0, 0.0, Some(Vec3::new(1.0, 0.0, 1e-6)))),
        );
        let dirs = [
            Vec3::Z,
            -Vec3::Z,
            Vec3::new(1.0, 0.0, 1e-7).normalize(),
            Vec3::new(0.3, 0.4, -0.866),
            Vec3::new(0.0, 1.0, 0.0),
        ];
        for &wo in &dirs {
            for &wi in &dirs {
                assert!(bsdf.f(wo, wi).0.iter().all(|v| v.is_finite()), "{wo} {wi}");
                assert!(bsdf.pdf(wo, wi).is_finite());
            }
            for uc in [0.0, 0.5, 0.999] {
                if let Some(s) = bsdf.sample(wo, uc, Vec2::new(0.3, 0.7)) {
                    assert!(s.f.0.iter().all(|v| v.is_finite()) && s.pdf[0].is_finite());
                }
            }
        }
    }
}

mod transmission {
    use super::*;
    use prism_scene::bsdf::{
        Ggx, Glass, RoughDielectric, ThinDielectric, Transmissive, TransportMode,
    };

    fn thin(roughness: f32) -> ThinDielectric<4> {
        let a = roughness * roughness;
        ThinDielectric {
            distribution: Ggx::new(a, a),
            eta: [1.5, 1.5, 1.52, 1.55],
        }
    }

    /// A thin sheet conserves energy: smooth, its reflectance and transmittance sum to 1
    /// (the slab's R' = 2R / (1 + R)); at normal incidence R' is 2 x 0.04 / 1.04; the
    /// transmitted direction is straight through. Rough, it keeps what single-scattering
    /// GGX keeps (more than 90% at roughness 0.3 head-on), never more than 1.
    #[test]
    fn a_thin_sheet_conserves_energy_and_does_not_bend_light() {
        let smooth = thin(0.0);
        let wo = Vec3::new(0.3, -0.2, 0.93).normalize();
        let reflected = smooth.sample(wo, 0.0, Vec2::ZERO).unwrap();
        let crossed = smooth.sample(wo, 0.999, Vec2::ZERO).unwrap();
        assert!(reflected.delta && crossed.delta);
        assert!((crossed.wi + wo).length() < 1e-6, "{}", crossed.wi);
        for k in 0..4 {
            assert!((reflected.pdf[k] + crossed.pdf[k] - 1.0).abs() < 1e-6);
        }
        let head_on = smooth.sample(Vec3::Z, 0.0, Vec2::ZERO).unwrap();
        assert!(
            (head_on.pdf[0] - 0.08 / 1.04).abs() < 1e-5,
            "{}",
            head_on.pdf[0]
        );
        for roughness in [0.1f32, 0.3, 0.7] {
            let sheet = thin(roughness);
            for wo in outgoing() {
                let a = albedo(|w, uc, u| sheet.sample(w, uc, u), wo)[0];
                assert!(a <= 1.0 + 5e-3, "roughness {roughness}, wo {wo}: {a}");
                if roughness <= 0.3 && wo.z > 0.5 {
                    assert!(a > 0.9, "roughness {roughness}, wo {wo}: {a}");
                }
            }
        }
    }

    #[test]
    fn sampling_matches_its_density_and_is_reciprocal() {
        let base =
            MetallicRoughness::new(SampledSpectrum([0.8, 0.5, 0.3, 0.1]), 0.0, 0.5, &COATING);
        for (k, glass) in [
            Glass::Thin(thin(0.4)),
            Glass::Thick(RoughDielectric {
                distribution: Ggx::new(0.2, 0.2),
                eta: [1.5; 4],
                mode: TransportMode::Radiance,
            }),
        ]
        .into_iter()
        .enumerate()
        {
            for transmission in [1.0f32, 0.4] {
                let bsdf = Transmissive {
                    glass,
                    tint: SampledSpectrum([1.0, 0.8, 0.5, 0.2]),
                    opaque: base.clone(),
                    transmission,
                };
                for (j, wo) in [
                    Vec3::new(0.5, 0.2, 0.84).normalize(),
                    Vec3::new(0.1, -0.9, -0.4).normalize(),
                ]
                .into_iter()
                .enumerate()
                {
                    chi_square_directions(
                        &format!("transmissive {k} {transmission} wo {j}"),
                        |u| {
                            let (uc, u) = split(u);
                            bsdf.sample(wo, uc, u).map(|s| s.wi)
                        },
                        |wi| f64::from(bsdf.pdf(wo, wi)),
                    );
                }
            }
        }
        let sheet = thin(0.4);
        let mut stream = IndependentStream::new(73, 0, 0);
        for _ in 0..2000 {
            let wo = prism_sampling::warp::cosine_hemisphere(stream.next_2d());
            let mut wi = prism_sampling::warp::cosine_hemisphere(stream.next_2d());
            if stream.next_1d() < 0.5 {
                wi.z = -wi.z;
            }
            let (x, y) = (sheet.f(wo, wi), sheet.f(wi, wo));
            for k in 0..4 {
                assert!(
                    (x[k] - y[k]).abs() <= 1e-4 * x[k].abs().max(1.0),
                    "{x:?} {y:?}"
                );
            }
        }
    }

    /// Transmission factor t: white furnace of a white thin sheet at t = 1 (smooth: all
    /// of it, reflected or crossed) and of a half-glass half-white-base mix; the tint
    /// colours only what crosses.
    #[test]
    fn the_mix_conserves_energy_and_the_tint_colours_what_crosses() {
        let white = MetallicRoughness::new(SampledSpectrum([1.0; 4]), 0.0, 0.5, &COATING);
        for transmission in [1.0f32, 0.5] {
            let bsdf = Transmissive {
                glass: Glass::Thin(thin(0.0)),
                tint: SampledSpectrum([1.0; 4]),
                opaque: white.clone(),
                transmission,
            };
            for wo in outgoing() {
                for (k, a) in albedo(|w, uc, u| bsdf.sample(w, uc, u), wo)
                    .into_iter()
                    .enumerate()
                {
                    assert!(
                        (a - 1.0).abs() < 8e-3,
                        "t {transmission}, wo {wo}, lane {k}: {a}"
                    );
                }
            }
        }
        let tinted = Transmissive {
            glass: Glass::Thin(thin(0.0)),
            tint: SampledSpectrum([1.0, 0.5, 0.25, 0.0]),
            opaque: white.clone(),
            transmission: 1.0,
        };
        let crossed = tinted.sample(Vec3::Z, 0.999, Vec2::ZERO).unwrap();
        let reflected = tinted.sample(Vec3::Z, 0.0, Vec2::ZERO).unwrap();
        assert_eq!(crossed.f[3], 0.0);
        assert!((crossed.f[1] / crossed.f[0] - 0.5).abs() < 1e-5);
        assert!((reflected.f[1] - reflected.f[0]).abs() < 1e-6 && reflected.f[3] > 0.0);
    }
}

mod diffuse_transmission {
    use super::*;
    use prism_scene::bsdf::DiffuseTransmission;

    fn leaf(
        base: f32,
        factor: f32,
        color: [f32; 4],
        roughness: f32,
    ) -> MetallicRoughness<'static, 4> {
        MetallicRoughness::new(SampledSpectrum([base; 4]), 0.0, roughness, &COATING)
            .with_diffuse_transmission(DiffuseTransmission {
                factor,
                color: SampledSpectrum(color),
            })
    }

    /// White furnace over both sides: a white base with a white transmission colour
    /// reflects and transmits everything between them, whatever the share; the share
    /// moves light from one side to the other.
    #[test]
    fn reflection_and_transmission_sum_to_everything() {
        for factor in [0.25f32, 1.0] {
            for roughness in [0.3f32, 0.8] {
                let bsdf = leaf(1.0, factor, [1.0; 4], roughness);
                for wo in outgoing() {
                    let a = albedo(|w, uc, u| bsdf.sample(w, uc, u), wo)[0];
                    assert!(
                        (a - 1.0).abs() < 8e-3,
                        "factor {factor}, roughness {roughness}, wo {wo}: {a}"
                    );
                }
            }
        }
        // How much crosses: the share of the diffuse base, coloured.
        let bsdf = leaf(1.0, 0.5, [1.0, 0.5, 0.0, 1.0], 0.5);
        let (wo, wi) = (
            Vec3::new(0.2, 0.1, 0.97).normalize(),
            Vec3::new(-0.3, 0.2, -0.93).normalize(),
        );
        let f = bsdf.f(wo, wi);
        assert!(
            f[0] > 0.0 && (f[1] / f[0] - 0.5).abs() < 1e-5 && f[2] == 0.0,
            "{f:?}"
        );
        assert_eq!(leaf(1.0, 0.0, [1.0; 4], 0.5).f(wo, wi).0, [0.0; 4]);
    }

    /// Under a white sheen and a clear coat, a white translucent base still keeps
    /// everything between reflection and transmission; sampling matches the density.
    #[test]
    fn layers_over_a_translucent_base() {
        use prism_scene::bsdf::{Clearcoat, Layered, Sheen, TransportMode};
        let bsdf = Layered {
            base: leaf(1.0, 0.7, [1.0; 4], 0.5),
            sheen: Some(Sheen::new(SampledSpectrum([1.0; 4]), 0.4)),
            clearcoat: Some(Clearcoat::new(1.0, 0.1, None)),
            mode: TransportMode::Radiance,
        };
        for wo in outgoing() {
            let a = albedo(|w, uc, u| bsdf.sample(w, uc, u), wo)[0];
            assert!((a - 1.0).abs() < 0.015, "wo {wo}: {a}");
        }
        let wo = Vec3::new(0.5, 0.2, 0.84).normalize();
        chi_square_directions(
            "layered translucent",
            |u| {
                let (uc, u) = split(u);
                bsdf.sample(wo, uc, u).map(|s| s.wi)
            },
            |wi| f64::from(bsdf.pdf(wo, wi)),
        );
    }

    #[test]
    fn sampling_matches_its_density_and_is_reciprocal() {
        let bsdf = leaf(0.7, 0.6, [0.9, 0.6, 0.3, 0.1], 0.4);
        for (k, wo) in [
            Vec3::new(0.5, 0.2, 0.84).normalize(),
            Vec3::new(0.1, -0.9, -0.4).normalize(),
        ]
        .into_iter()
        .enumerate()
        {
            chi_square_directions(
                &format!("diffuse transmission wo {k}"),
                |u| {
                    let (uc, u) = split(u);
                    bsdf.sample(wo, uc, u).map(|s| s.wi)
                },
                |wi| f64::from(bsdf.pdf(wo, wi)),
            );
        }
        let mut stream = IndependentStream::new(79, 0, 0);
        for _ in 0..2000 {
            let wo = prism_sampling::warp::cosine_hemisphere(stream.next_2d());
            let mut wi = prism_sampling::warp::cosine_hemisphere(stream.next_2d());
            if stream.next_1d() < 0.5 {
                wi.z = -wi.z;
            }
            let (x, y) = (bsdf.f(wo, wi), bsdf.f(wi, wo));
            for k in 0..4 {
                assert!(
                    (x[k] - y[k]).abs() <= 1e-4 * x[k].abs().max(1.0),
                    "{x:?} {y:?}"
                );
            }
        }
    }
}
/// The extensions' state is allocated only for materials that have it: the BSDF every
/// hit builds and moves stays as small as before they existed (it was 360 bytes at 8
/// lanes with the state inline, and cost the Cornell box more instructions).
#[test]
fn a_bsdf_without_extensions_stays_small() {
    let size = std::mem::size_of::<prism_scene::world::Bsdf<'static, 8>>();
    assert!(size <= 96, "Bsdf<8> is {size} bytes");
}

/// No NaN or infinity escapes the extensions' lobes, for any parameters (including NaN,
/// infinities and values out of range) and any directions, including grazing ones and
/// directions on either side.
mod extremes {
    use super::*;
    use prism_scene::bsdf::{
        Clearcoat, DiffuseTransmission, Ggx, Glass, Iridescence, Layered, RoughDielectric, Sheen,
        ThinDielectric, ThinFilm, Transmissive, TransportMode,
    };
    use proptest::prelude::*;

    fn any_f32() -> impl Strategy<Value = f32> {
        prop_oneof![
            -2.0f32..3.0,
            Just(f32::NAN),
            Just(f32::INFINITY),
            Just(f32::NEG_INFINITY),
            Just(0.0f32),
            Just(1.0f32),
        ]
    }

    fn direction() -> impl Strategy<Value = Vec3> {
        (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0)
            .prop_map(|(x, y, z)| Vec3::new(x, y, z).normalize_or(Vec3::new(1.0, 0.0, 1e-7)))
    }

    fn finite(s: &SampledSpectrum<4>) -> bool {
        s.0.iter().all(|v| v.is_finite() && *v >= 0.0)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(400))]
        #[test]
        fn every_lobe_stays_finite(
            params in proptest::collection::vec(any_f32(), 12),
            wo in direction(),
            wi in direction(),
            uc in 0.0f32..1.0,
            u in (0.0f32..1.0, 0.0f32..1.0),
        ) {
            let p = |i: usize| params[i];
            let base = MetallicRoughness::new(SampledSpectrum([p(0); 4]), p(1), p(2), &COATING)
                .with_specular(Specular { weight: p(3), color: SampledSpectrum([p(4); 4]) })
                .with_diffuse_transmission(DiffuseTransmission { factor: p(5), color: SampledSpectrum([p(6); 4]) })
                .with_anisotropy(p(7), Vec2::new(p(8), p(9)))
                .with_iridescence(Iridescence {
                    factor: p(10),
                    film: ThinFilm { ior: p(11), thickness_nm: p(9) * 500.0 },
                    lambdas: [450.0, 520.0, 590.0, 660.0],
                    iors: None,
                });
            let layered = Layered {
                base: base.clone(),
                sheen: Some(Sheen::new(SampledSpectrum([p(6); 4]), p(7))),
                clearcoat: Some(Clearcoat::new(p(8), p(9), Some(Vec3::new(p(10), p(11), p(0))))),
                mode: TransportMode::Radiance,
            };
            let a = p(2) * p(2);
            let glass = |thin: bool| if thin {
                Glass::Thin(ThinDielectric { distribution: Ggx::new(a, a), eta: [p(11).abs().max(1e-3); 4] })
            } else {
                // The thick dielectric's own tests cover its index; the scene gives it a
                // finite one.
                Glass::Thick(RoughDielectric { distribution: Ggx::new(a, a), eta: [if p(11).is_finite() { p(11).abs().clamp(1e-3, 10.0) } else { 1.5 }; 4], mode: TransportMode::Radiance })
            };
            let u = Vec2::new(u.0, u.1);
            for thin in [true, false] {
                let t = Transmissive { glass: glass(thin), tint: SampledSpectrum([p(4); 4]), opaque: base.clone(), transmission: p(3) };
                prop_assert!(finite(&t.f(wo, wi)) && t.pdf(wo, wi).is_finite());
                if let Some(s) = t.sample(wo, uc, u) {
                    prop_assert!(finite(&s.f) && s.pdf.iter().all(|v| v.is_finite()) && s.wi.is_finite());
                }
            }
            prop_assert!(finite(&base.f(wo, wi)) && base.pdf(wo, wi).is_finite());
            prop_assert!(finite(&layered.f(wo, wi)) && layered.pdf(wo, wi).is_finite());
            for s in [base.sample(wo, uc, u), layered.sample(wo, uc, u)].into_iter().flatten() {
                prop_assert!(finite(&s.f) && s.pdf.iter().all(|v| v.is_finite()) && s.wi.is_finite());
            }
        }
    }
}
