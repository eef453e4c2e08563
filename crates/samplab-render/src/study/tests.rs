//! Tests of [`super`].

use super::*;

/// What a front end's arguments become: each read by its declared type, defaults
/// filled in, the wrong types refused by name (a float count is not truncated).
#[test]
fn arguments_are_read_by_their_declared_types() {
    let (study, per_chunk) =
        read(r#"{"kind": "integrate", "samplers": "random", "integrand": "quad", "n": 16}"#).unwrap();
    let described: Value = serde_json::from_str(&study.to_json()).unwrap();
    assert_eq!(described["samplers"], serde_json::json!(["random"]));
    assert_eq!(described["n"], serde_json::json!([16]));
    assert_eq!((described["sets"].as_u64(), described["seed"].as_u64()), (Some(50), Some(samplab::Seed::DEFAULT.0)));
    assert_eq!(per_chunk, 1);
    let refused = |arguments: &str| read(arguments).unwrap_err().to_string();
    let integrate =
        |extra: &str| format!(r#"{{"kind": "integrate", "samplers": ["random"], "integrand": "quad", {extra}}}"#);
    assert_eq!(refused(&integrate(r#""n": [16.7]"#)), "n = 16.7: must be a whole number");
    assert_eq!(refused(&integrate(r#""n": 64.0"#)), "n = 64.0: must be a whole number");
    assert_eq!(refused(&integrate(r#""n": [true]"#)), "n = true: must be a whole number");
    assert_eq!(refused(&integrate(r#""n": [-1]"#)), "n = -1: out of range [0, 2^64)");
    assert_eq!(
        refused(&integrate(r#""n": 16, "units_per_chunk": 2.5"#)),
        "units_per_chunk = 2.5: must be a whole number"
    );
    assert!(
        refused(r#"{"kind": "integrate", "integrand": "quad", "n": 16}"#).starts_with("samplers = null: must be given")
    );
    assert!(refused(r#"{"kind": "spectra"}"#).contains("unknown study kind 'spectra'"));
    assert!(
        refused(r#"{"kind": "render", "scene": "box", "seeds": 1, "seed": 3}"#).contains("give the seeds as `seeds`")
    );
    // a keyword no parameter declares: refused where the kind has no rest, with the
    // closest names; a render setting side by side with a render study's parameters
    assert_eq!(
        refused(&integrate(r#""n": 16, "set": 6"#)),
        "unknown study parameter 'set' (did you mean sets, seed, d?)"
    );
    let (render, _) = read(r#"{"kind": "render", "scene": "spheres", "seeds": 1, "n": 4, "res": [32, 24]}"#).unwrap();
    let described: Value = serde_json::from_str(&render.to_json()).unwrap();
    assert_eq!(
        (&described["settings"]["n"], &described["settings"]["res"]),
        (&serde_json::json!(4), &serde_json::json!([32, 24]))
    );
    assert!(refused(r#"{"kind": "render", "scene": "spheres", "seeds": 1, "nn": 4}"#).contains("nn"));
}

fn study(seeds: Vec<u64>) -> Study {
    let settings = Settings { n: 4, res: Some((24, 16)), ..Settings::default() };
    Study::Render(Box::new(RenderStudy {
        scene: "spheres".into(),
        light: None,
        reference_samples: 64,
        penumbra: false,
        settings,
        seeds,
    }))
}

/// Chunked, the study's errors are those of each seed's render against the reference,
/// rendered directly; the description survives its JSON.
#[test]
fn chunked_render_errors_equal_the_direct_ones() {
    let (s, chunks) = study(vec![3, 9, 4]).plan(2).unwrap();
    assert_eq!(chunks, vec![vec![], vec![3, 9], vec![4]]);
    assert_eq!(Study::from_json(&s.to_json()).unwrap(), s);
    let first = s.compute(&chunks[0], None, None, &Progress::SILENT).unwrap();
    let parts: Vec<Vec<u8>> = std::iter::once(first.clone())
        .chain(chunks[1..].iter().map(|c| s.compute(c, Some(&first), None, &Progress::SILENT).unwrap()))
        .collect();
    let merged: Value = serde_json::from_str(&s.merge(&parts).unwrap().json).unwrap();
    let scene = load_scene("spheres", None, Paths::InsideScene).unwrap();
    let Study::Render(r) = &s else { unreachable!() };
    let reference_options = r.settings.options(&scene).unwrap().reference(&scene, 64).unwrap();
    let reference = crate::render(&scene, &reference_options, &Progress::SILENT).unwrap().image;
    assert_eq!(Image::from_bytes(&first).unwrap(), reference);
    for (k, seed) in [3, 9, 4].into_iter().enumerate() {
        let settings = Settings { seed, ..r.settings.clone() };
        let image = crate::render(&scene, &settings.options(&scene).unwrap(), &Progress::SILENT).unwrap().image;
        let rmse = image.errors(&reference, false).unwrap().rmse;
        assert_eq!(merged["errors"][k]["rmse"].as_f64().unwrap().to_bits(), rmse.to_bits(), "seed {seed}");
    }
    assert!(s.compute(&[3], None, None, &Progress::SILENT).is_err(), "an error chunk without its reference");
}

/// Each kind's declared parameters are exactly its description's fields: a front end
/// built from [`KINDS`] can give every field and nothing else.
#[test]
fn every_kind_declares_its_description_fields() {
    let library = |text: &str| Study::from_json(text).unwrap().to_json();
    let examples = [
        library(
            r#"{"kind":"integrate","samplers":["random"],"integrand":"f","n":[16],"sets":2,"instances":1,"seed":1,"d":2,"exact":0.5}"#,
        ),
        library(
            r#"{"kind":"spectrum","sampler":"jitter","n":16,"d":2,"sets":2,"res":8,"direct":false,"tolerance":1e-9,"seed":1}"#,
        ),
        library(
            r#"{"kind":"discrepancy","metrics":["star"],"sampler":"jitter","n":16,"d":2,"sets":2,"seed":1,"max_work":null}"#,
        ),
        study(vec![1]).to_json(),
    ];
    assert_eq!(KINDS.len(), examples.len());
    for (kind, example) in KINDS.iter().zip(&examples) {
        let value: Value = serde_json::from_str(example).unwrap();
        let fields: std::collections::BTreeSet<&str> =
            value.as_object().unwrap().keys().map(String::as_str).filter(|k| *k != "kind").collect();
        let declared: std::collections::BTreeSet<&str> =
            kind.parameters.iter().map(|p| p.name).chain(kind.rest).collect();
        assert_eq!(value["kind"], kind.kind);
        assert_eq!(fields, declared, "{}", kind.kind);
        for p in kind.parameters.iter().filter_map(|p| p.default) {
            serde_json::from_str::<Value>(p).unwrap();
        }
    }
}

#[test]
fn image_bytes_round_trip_and_bad_bytes_are_refused() {
    let image =
        Image { width: 2, height: 1, rgb: vec![0.5, 1.0, 2.0, 3.0, 4.0, 5.0], visibility: Some(vec![0.0, 1.0]) };
    assert_eq!(Image::from_bytes(&image.to_bytes()).unwrap(), image);
    let plain = Image { visibility: None, ..image.clone() };
    assert_eq!(Image::from_bytes(&plain.to_bytes()).unwrap(), plain);
    let bytes = image.to_bytes();
    assert!(Image::from_bytes(&bytes[..bytes.len() - 1]).is_err());
    assert!(Image::from_bytes(&[0; 5]).is_err());
    assert!(study(vec![]).plan(1).is_err());
    assert!(study(vec![1]).plan(0).is_err());
}
