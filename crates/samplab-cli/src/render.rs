//! `samplab render`: soft shadows with any strategy per pixel, against a reference.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, bail};
use samplab_render::mitsuba::Paths;
use samplab_render::scenes;
use samplab_render::settings::{self, Settings};
use samplab_render::{Image, Options, Scene, render};

use crate::bar::Bar;

/// The examples, and the built-in scenes with what each shows (from the scene registry).
fn after_help() -> String {
    let scenes: String =
        scenes::SCENES.iter().map(|b| format!("  {:<16}{}\n", b.about.name, b.about.summary)).collect();
    format!(
        "Examples:\n  samplab render spheres --light disk --sampler jitter.uniform -n 25 --disk-map reject \\\n      \
         -o uj.exr --reference ref.exr --error-image err.png\n  samplab render grids --light linear --sampler jitter -n 16 -o strat.png\n  \
         samplab render scene.xml --sampler sobol.owen -n 4 --spp 16 --pixel area --mode direct -o out.exr\n  \
         samplab render sphere-box --mode obscurance --range 0.5 --sampler systematic -n 16 -o ao.png\n  \
         samplab render checker-45 --pixel area --spp 16 --area-sampler halton.shift --interleave 4x1 \\\n      \
         -o il.png\n\n\
         SCENE is a built-in scene or a Mitsuba 3 XML file. Built-in scenes:\n{scenes}\n\
         A missing --reference file is rendered (sobol.owen, --reference-samples light samples, 64 pixel \
         samples in area mode) and kept for the next run."
    )
}

/// Render a scene with a sampling strategy per pixel.
#[derive(clap::Args)]
#[command(after_help = after_help())]
pub struct Args {
    /// A built-in scene name or a Mitsuba 3 .xml file
    scene: String,
    /// Let a Mitsuba scene name files outside its own folder (`..`, absolute paths, links
    /// leading out): only for scenes you trust
    #[arg(long)]
    allow_paths_outside_scene: bool,
    /// Replace a built-in scene's light: square, disk, linear, gaussian
    #[arg(long)]
    light: Option<String>,
    /// The render settings (one table: `samplab_render::Settings`)
    #[command(flatten)]
    settings: Settings,
    /// Output image (.exr linear with a visibility channel V, or .png sRGB)
    #[arg(short, long)]
    output: PathBuf,
    /// Reference image (.exr) to measure the error against; rendered and kept if missing
    #[arg(long)]
    reference: Option<PathBuf>,
    /// Light samples per estimate of a reference rendered here
    #[arg(long, default_value_t = 4096)]
    reference_samples: usize,
    /// Restrict the error to the reference's penumbra (0 < V < 1)
    #[arg(long)]
    penumbra: bool,
    /// Write the signed error (red: too bright, green: too dark) as a PNG
    #[arg(long)]
    error_image: Option<PathBuf>,
    /// Scale of the error image
    #[arg(long, default_value_t = 10.0)]
    error_scale: f64,
    /// Print the summary as JSON on stdout
    #[arg(long)]
    json: bool,
}

fn check_extension(flag: &str, path: &Path, allowed: &[&str]) -> anyhow::Result<()> {
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
    if !allowed.contains(&ext.as_str()) {
        bail!("{flag}: {} must end in .{}", path.display(), allowed.join(" or ."));
    }
    Ok(())
}

pub fn run(a: &Args) -> anyhow::Result<()> {
    check_extension("--output", &a.output, &["exr", "png"])?;
    if let Some(p) = &a.reference {
        check_extension("--reference", p, &["exr"])?;
    }
    if let Some(p) = &a.error_image {
        check_extension("--error-image", p, &["png"])?;
        if a.reference.is_none() {
            bail!("--error-image needs --reference");
        }
    }
    {
        use samplab::io::Role;
        let reference = a
            .reference
            .as_deref()
            .map(|p| if p.exists() { Role::Input("--reference", p) } else { Role::File("--reference", p) });
        let roles = [
            Some(Role::Input("the scene", Path::new(&a.scene))),
            Some(Role::File("--output", &a.output)),
            reference,
            a.error_image.as_deref().map(|p| Role::File("--error-image", p)),
        ];
        // with the files the samplers read (a pixel family reads none)
        let roles: Vec<Role<'_>> = roles.into_iter().flatten().collect();
        let s = &a.settings;
        let specs = [&s.sampler, &s.area_sampler, &s.lens_sampler, &s.time_sampler, &s.gloss_sampler];
        let specs: Vec<&str> = specs.into_iter().chain(&s.pixel_sampler).map(String::as_str).collect();
        crate::refuse_overlap(&specs, &roles)?;
        for role in &roles {
            if let Role::File(_, p) = role {
                samplab::io::check_file(p)?;
            }
        }
    }
    if a.penumbra && a.reference.is_none() {
        bail!("--penumbra needs --reference");
    }
    if !(a.error_scale.is_finite() && a.error_scale > 0.0) {
        bail!("--error-scale: {} must be a positive number", a.error_scale);
    }
    let paths = if a.allow_paths_outside_scene { Paths::Anywhere } else { Paths::InsideScene };
    let scene = settings::load_scene(&a.scene, a.light.as_deref(), paths)?;
    let settings = &a.settings;
    let options = settings.options(&scene)?;
    let (width, height) = (options.width, options.height);
    // every output is staged and appears with the others, or none does
    let mut outputs = samplab::io::Staged::new();
    let reference = match &a.reference {
        Some(path) if path.exists() => Some((Image::read_exr(path)?, false)),
        Some(path) => {
            let r = render_reference(&scene, &options, a.reference_samples)?;
            r.stage_exr(&mut outputs, path)?;
            Some((r, true))
        }
        None => None,
    };
    let started = Instant::now();
    let bar = Bar::new(height as u64, "rows");
    let rendered = render(&scene, &options, &bar.progress())?;
    drop(bar);
    let seconds = started.elapsed().as_secs_f64();
    let errors = match &reference {
        Some((r, _)) => Some(rendered.image.errors(r, a.penumbra).context("--reference")?),
        None => None,
    };
    if let (Some(path), Some((r, _))) = (&a.error_image, &reference) {
        samplab_render::image::stage_png(&rendered.image.error_image(r, a.error_scale)?, &mut outputs, path)?;
    }
    rendered.image.stage(&mut outputs, &a.output)?;
    let rays = rendered.camera_rays + rendered.shadow_rays;
    // a pixel sampler draws every dimension, the light samples too
    let sampler = options.light_source();
    let mut summary = serde_json::json!({
        "scene": a.scene, "sampler": sampler, "n": settings.n, "spp": settings.spp, "mode": settings.mode,
        "pixel": options.footprint.name(), "width": width, "height": height, "seed": settings.seed, "seconds": seconds,
        "camera_rays": rendered.camera_rays, "shadow_rays": rendered.shadow_rays,
        "rays_per_second": rays as f64 / seconds, "errors": errors,
        "penumbra_only": a.penumbra,
        "reference_rendered": reference.as_ref().map(|r| r.1),
    });
    if let samplab_render::Mode::Path { max_depth } = options.mode {
        summary["max_depth"] = max_depth.into();
    }
    outputs.commit()?;
    if a.json {
        crate::emit(None, format!("{}\n", serde_json::to_string_pretty(&summary)?).as_bytes())?;
    }
    // light samples per estimate, or a path's most segments
    let per = match options.mode {
        samplab_render::Mode::Path { max_depth } => format!("depth {max_depth}"),
        _ => format!("x{}", settings.n),
    };
    let error_text = errors.map_or(String::new(), |e| {
        format!(
            "; vs reference{}: RMSE {:.4e}, relative {:.2}%, mean |E| {:.4e}",
            if a.penumbra { " (penumbra)" } else { "" },
            e.rmse,
            100.0 * e.relative,
            e.mean_abs
        )
    });
    crate::say!(
        "{} {width}x{height}, {} {per} x{} spp, seed {}: {seconds:.2} s, {:.1} M rays/s{error_text} -> {}",
        a.scene,
        sampler,
        settings.spp,
        settings.seed,
        rays as f64 / seconds / 1e6,
        a.output.display()
    );
    Ok(())
}

/// The converged reference for `options` ([`Options::reference`]), with a progress bar.
fn render_reference(scene: &Scene, options: &Options, samples: usize) -> anyhow::Result<Image> {
    let reference = options.reference(scene, samples)?;
    let bar = Bar::new(options.height as u64, "reference rows");
    Ok(render(scene, &reference, &bar.progress())?.image)
}
