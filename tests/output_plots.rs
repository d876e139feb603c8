//! Plots: axis titles with units in the SVG text, the post-buckling panel covering
//! [0.9 λ_c, end], legends outside every data area, the "not wrinkled" map, PNG sizes.
//!
//! The responses are shaped like the default scene (λ_c = 0.08952 N/mm, amplitude rising like
//! a square root past the threshold to max |w|/h = 4) and the long strip (λ in mm, loss of
//! ellipticity before the threshold).

use std::f64::consts::PI;
use std::io;
use std::path::{Path, PathBuf};
use wrinkle::output::plots::rectangles_overlap;
use wrinkle::output::{
    ClosedFormCurve, GridField, LoadMarker, PlotOutput, Profile, ProfilePlot, Quantity, Response,
    ResponsePoint, WrinkleMap, plot_comparison, plot_profiles, plot_response, plot_wrinkle_map,
};

fn scratch_dir(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("wrinkle-plots-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Width and height from the IHDR chunk, after checking the PNG signature.
fn png_size(file: &Path) -> (u32, u32) {
    let bytes = std::fs::read(file).unwrap();
    assert_eq!(bytes[..8], [0x89, b'P', b'N', b'G', 0x0d, 0x0a, 0x1a, 0x0a]);
    assert_eq!(&bytes[12..16], b"IHDR");
    let word = |at: usize| u32::from_be_bytes(bytes[at..at + 4].try_into().unwrap());
    (word(16), word(20))
}

fn svg_text(output: &PlotOutput) -> String {
    let svg = output
        .files
        .iter()
        .find(|f| f.extension().is_some_and(|e| e == "svg"))
        .unwrap();
    // Text is escaped in SVG; compare with the unescaped form.
    std::fs::read_to_string(svg)
        .unwrap()
        .replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&amp;", "&")
}

/// A path shaped like the default scene's: flat, then a square root past λ_c.
fn biaxial_response(critical: f64, end_ratio: f64) -> Response {
    let points: Vec<ResponsePoint> = (0..=200)
        .map(|k| {
            let load = critical * end_ratio * k as f64 / 200.0;
            let excess = (load / critical - 1.0).max(0.0);
            ResponsePoint {
                load,
                max_amplitude_over_h: 6e-5 + 8.0 * excess.sqrt(),
                centre_amplitude_over_h: Some(6e-5 + 2.0 * excess.sqrt()),
                step_end: k % 20 == 0,
            }
        })
        .collect();
    let closed = (0..=50)
        .map(|k| {
            let ratio = 1.0 + (end_ratio - 1.0) * k as f64 / 50.0;
            (ratio, 2.5 * (ratio - 1.0).sqrt())
        })
        .collect();
    let load = Quantity::biaxial_load();
    Response::new("reference-envelope", load.clone(), critical, points)
        .with_closed_form(ClosedFormCurve {
            label: "one-mode closed form (62)".into(),
            points: closed,
        })
        .with_marker(LoadMarker::linear_buckling(critical, &load))
}

fn assert_legend_outside(output: &PlotOutput) {
    let legend = output.layout.legend.expect("a legend");
    let (width, height) = output.layout.size;
    assert!(legend[0] >= 0 && legend[1] >= 0);
    assert!(legend[2] <= width as i32 && legend[3] <= height as i32);
    for panel in &output.layout.panels {
        assert!(
            !rectangles_overlap(legend, panel.plot_area),
            "legend {legend:?} overlaps the data area {:?} of `{}`",
            panel.plot_area,
            panel.title
        );
    }
}

#[test]
fn response_plot_has_units_a_post_buckling_panel_and_the_legend_below() {
    let dir = scratch_dir("response");
    let critical = 0.0895213;
    let response = biaxial_response(critical, 1.25);
    let output = plot_response(&dir.join("response"), "Default scene", &response).unwrap();
    assert_eq!(png_size(&output.files[0]), output.layout.size);

    let [whole, zoom] = &output.layout.panels[..] else {
        panic!("two panels expected");
    };
    assert_eq!(whole.axis_titles.0, "load λ = −N_X (N/mm)");
    assert_eq!(whole.axis_titles.1, "physical amplitude max |w| / h");
    assert!(whole.x_range.0 <= 0.0 && whole.x_range.1 >= 1.25 * critical);
    // The zoomed panel covers [0.9 λ_c, end] in λ/λ_c, and not much more.
    assert_eq!(zoom.axis_titles.0, "load ratio λ / λ_c");
    assert_eq!(zoom.x_range.0, 0.9);
    assert!(
        zoom.x_range.1 >= 1.25 && zoom.x_range.1 < 1.3,
        "{:?}",
        zoom.x_range
    );
    assert!(zoom.y_range.0 <= 0.0 && zoom.y_range.1 >= 4.0);

    let svg = svg_text(&output);
    for text in [
        "Default scene",
        "load λ = −N_X (N/mm)",
        "load ratio λ / λ_c",
        "physical amplitude max |w| / h",
        "one-mode closed form (62)",
        "linear buckling λ_c = 0.089521 N/mm",
        "|w| / h at the centre",
        "λ_c",
    ] {
        assert!(svg.contains(text), "SVG lacks `{text}`");
    }
    assert_legend_outside(&output);
    let legend = output.layout.legend.unwrap();
    assert!(legend[1] >= whole.plot_area[3], "legend below the panels");
}

#[test]
fn strip_response_shows_the_ellipticity_marker_outside_the_legend() {
    let dir = scratch_dir("strip");
    let load = Quantity::end_displacement();
    let critical = 14.47;
    let points = (0..=100)
        .map(|k| {
            let u = 24.64 * k as f64 / 100.0;
            ResponsePoint {
                load: u,
                max_amplitude_over_h: 4.0 * ((u - critical).max(0.0) / 10.17).sqrt(),
                centre_amplitude_over_h: None,
                step_end: k % 10 == 0,
            }
        })
        .collect();
    let response = Response::new("reference-envelope", load.clone(), critical, points)
        .with_marker(LoadMarker::linear_buckling(critical, &load))
        .with_marker(LoadMarker::loss_of_ellipticity(3.746, Some(3.4e-4), &load));
    let output = plot_response(&dir.join("strip"), "Long strip", &response).unwrap();
    let svg = svg_text(&output);
    for text in [
        "end displacement λ (mm)",
        "linear buckling λ_c = 14.470 mm",
        "loss of ellipticity at λ = 3.7460 mm on 0.034 % of the area",
        "ellipticity lost",
    ] {
        assert!(svg.contains(text), "SVG lacks `{text}`");
    }
    assert!(!svg.contains("at the centre"), "no centre curve was given");
    assert_legend_outside(&output);
}

#[test]
fn response_plot_rejects_unusable_input() {
    let dir = scratch_dir("response-errors");
    let stem = dir.join("bad");
    let mut response = biaxial_response(0.09, 1.2);
    response.critical_load = 0.0;
    let error = plot_response(&stem, "t", &response).unwrap_err();
    assert_eq!(error.kind(), io::ErrorKind::InvalidInput);
    let empty = Response::new("m", Quantity::biaxial_load(), 0.09, Vec::new());
    let error = plot_response(&stem, "t", &empty).unwrap_err();
    assert!(
        error.to_string().contains("no finite path point"),
        "{error}"
    );
    assert!(!dir.join("bad.png").exists());
}

#[test]
fn comparison_overlays_models_against_the_load_and_their_own_ratio() {
    let dir = scratch_dir("comparison");
    let mut first = biaxial_response(0.0895, 1.3);
    first.closed_form = None;
    let mut second = biaxial_response(0.0921, 1.2);
    second.model = "complex-envelope".into();
    for point in &mut second.points {
        point.max_amplitude_over_h *= 0.8;
    }
    let output = plot_comparison(
        &dir.join("comparison"),
        "Two models",
        &[first.clone(), second],
    )
    .unwrap();
    let svg = svg_text(&output);
    for text in [
        "reference-envelope (λ_c = 0.089500 N/mm)",
        "complex-envelope (λ_c = 0.092100 N/mm)",
        "load λ = −N_X (N/mm)",
        "load ratio λ / λ_c",
    ] {
        assert!(svg.contains(text), "SVG lacks `{text}`");
    }
    assert_eq!(output.layout.panels[1].x_range.0, 0.9);
    assert!(output.layout.panels[1].x_range.1 >= 1.3);
    assert_legend_outside(&output);

    let mut strip = first;
    strip.load = Quantity::end_displacement();
    let error = plot_comparison(
        &dir.join("mixed"),
        "t",
        &[biaxial_response(0.09, 1.2), strip],
    )
    .unwrap_err();
    assert!(error.to_string().contains("load units differ"), "{error}");
}

#[test]
fn profiles_have_a_titled_y_axis_the_location_and_a_legend_beside() {
    let dir = scratch_dir("profiles");
    let profiles = (1..=4)
        .map(|k| Profile {
            label: format!("λ = {:.4} N/mm", 0.09 + 0.005 * k as f64),
            points: (0..=400)
                .map(|i| {
                    let x = i as f64;
                    (x, k as f64 * (PI * x / 400.0).sin() * (0.2354 * x).cos())
                })
                .collect(),
        })
        .collect();
    let plot = ProfilePlot {
        abscissa: Quantity::coordinate("X"),
        ordinate: Quantity::deflection_over_thickness(),
        location: "along X at Y = 100.0 mm (through the maximum)".into(),
        profiles,
    };
    let output = plot_profiles(&dir.join("profile.at.max"), "Profiles", &plot).unwrap();
    assert!(
        dir.join("profile.at.max.png").exists(),
        "a dot in the stem is kept"
    );
    let svg = svg_text(&output);
    for text in [
        "X (mm)",
        "physical deflection w / h",
        "along X at Y = 100.0 mm (through the maximum)",
        "λ = 0.1100 N/mm",
    ] {
        assert!(svg.contains(text), "SVG lacks `{text}`");
    }
    assert_legend_outside(&output);
    let legend = output.layout.legend.unwrap();
    assert!(
        legend[0] >= output.layout.panels[0].plot_area[2],
        "legend to the right"
    );
}

fn wrinkled_field(length: f64, amplitude: f64) -> GridField {
    GridField::sample(
        Quantity::deflection(),
        [0.0, length, 0.0, 200.0],
        401,
        101,
        |x, y| amplitude * (PI * x / length).sin() * (PI * y / 200.0).sin() * (0.2354 * x).cos(),
    )
}

#[test]
fn wrinkle_map_has_a_labelled_colour_bar_and_keeps_the_aspect_ratio() {
    let dir = scratch_dir("map");
    for (length, name) in [(400.0, "short"), (1400.0, "long")] {
        let map = WrinkleMap::new(wrinkled_field(length, 0.2), 5e-5, "10⁻³ h");
        let max = wrinkle::output::quantity::format_significant(map.field.max_abs(), 4);
        let max = format!("max |w| = {max} mm;");
        let output = plot_wrinkle_map(&dir.join(name), "Wrinkles", &map).unwrap();
        assert_eq!(png_size(&output.files[0]), output.layout.size);
        let [left, top, right, bottom] = output.layout.panels[0].plot_area;
        let aspect = (right - left) as f64 / (bottom - top) as f64;
        assert!(
            (aspect - length / 200.0).abs() < 0.03 * length / 200.0,
            "{aspect}"
        );
        let bar = output.layout.color_bar.unwrap();
        assert!(bar[0] > right, "colour bar beside the map");
        let svg = svg_text(&output);
        for text in [
            "X (mm)",
            "Y (mm)",
            "physical deflection w (mm)",
            max.as_str(),
        ] {
            assert!(svg.contains(text), "SVG lacks `{text}`");
        }
        assert!(!svg.contains("not wrinkled"));
        // The field is one embedded PNG image, not one element per cell.
        assert_eq!(svg.matches("href=\"data:image/png;base64,").count(), 1);
    }
}

/// Samples 1 mm apart of a wave of 8 mm whose crests fall halfway between two samples miss
/// them: the largest sample is $`0.2\cos(\pi/8) = 0.1848`$ instead of the amplitude 0.2. Given the exact peak (as `wrinkle run` gives the nodal maximum), the map states
/// 0.2 mm, the number of the run's summary, and scales its colours to it.
#[test]
fn wrinkle_map_states_the_exact_peak_not_the_largest_sample() {
    let dir = scratch_dir("peak");
    let field = GridField::sample(
        Quantity::deflection(),
        [0.0, 400.0, 0.0, 200.0],
        401,
        101,
        |x, _| 0.2 * (PI / 4.0 * x + PI / 8.0).cos(),
    );
    let sampled = field.max_abs();
    assert!(
        (sampled - 0.2 * (PI / 8.0).cos()).abs() < 1e-12,
        "{sampled}"
    );
    let map = WrinkleMap::new(field.clone(), 5e-5, "10⁻³ h");
    assert!(map.note().starts_with(&format!(
        "max |w| = {} mm;",
        wrinkle::output::quantity::format_significant(sampled, 4)
    )));
    let map = WrinkleMap::new(field, 5e-5, "10⁻³ h").with_peak(0.2);
    assert_eq!(map.color_limit(), 0.2);
    let output = plot_wrinkle_map(&dir.join("peak"), "Wrinkles", &map).unwrap();
    assert!(
        svg_text(&output).contains("max |w| = 0.2000 mm;"),
        "{:?}",
        output.layout.notes
    );
}

#[test]
fn a_flat_field_is_drawn_pale_and_said_not_wrinkled() {
    let dir = scratch_dir("flat");
    // 1.5e-6 mm of pre-buckling response against a threshold of 10⁻³ h = 5e-5 mm.
    let map = WrinkleMap::new(wrinkled_field(400.0, 1.5e-6), 5e-5, "10⁻³ h");
    assert!(map.is_flat());
    assert_eq!(map.color_limit(), 5e-5);
    let output = plot_wrinkle_map(&dir.join("flat"), "Before buckling", &map).unwrap();
    assert!(
        output.layout.notes[0].starts_with("not wrinkled (max |w| = 1.50e-6 mm"),
        "{:?}",
        output.layout.notes
    );
    let svg = svg_text(&output);
    assert!(svg.contains("not wrinkled"));
    assert!(
        svg.contains("threshold 5.0e-5 mm = 10⁻³ h"),
        "the threshold is stated"
    );
}
