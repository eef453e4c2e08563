//! samplab-render: a soft-shadow ray tracer testbed for comparing sampling strategies.
//!
//! Each pixel's light samples are a point set from any samplab sampler, mapped to the light
//! area-preserving; pixel area, lens and shutter time have strategies of their own. The
//! renderer follows the set-ups of Ramamoorthi et al. 2012 (visibility sampling of linear,
//! square, circular and Gaussian lights), Subr & Kautz 2013 (secondary estimates, defocus,
//! motion blur), Shirley 1991 (checkerboards, a ball under two lights) and Sbert et al. 2006
//! (offsets x points per pixel).
#![deny(missing_docs)]

pub mod bsdf;
pub mod bvh;
pub mod camera;
pub mod error;
pub mod filter;
pub mod geometry;
pub mod image;
pub mod light;
pub mod mitsuba;
pub mod obj;
mod packet;
pub mod path;
pub mod render;
pub mod scene;
pub mod scenes;
pub mod settings;
pub mod study;

pub use error::{Error, Result};
pub use filter::Footprint;
pub use image::{Errors, Image};
pub use render::{Mode, Options, Pattern, Rendered, Sampling, Strategies, render};
pub use scene::Scene;
pub use settings::Settings;
