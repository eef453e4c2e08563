//! samplab-render's integration tests as one binary, each file a module (one link where
//! there were five).
#[path = "as_mitsuba.rs"]
mod as_mitsuba;
#[path = "mitsuba.rs"]
mod mitsuba;
#[path = "parsers.rs"]
mod parsers;
#[path = "path.rs"]
mod path;
#[path = "render.rs"]
mod render;
