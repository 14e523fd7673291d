//! `viewray serve`: the live playground in a browser.

use std::io::{IsTerminal, Write};
use std::net::IpAddr;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use clap::Args;
use viewray_serve::{ServeOptions, ServedScene, Server};

use crate::input::{DEFAULT_SCENE, DEFAULT_SCENE_PATH, STDIN_NAME, scene_error};
use crate::values::is_standard_stream;

#[derive(Args, Debug)]
pub(crate) struct ServeArgs {
    /// The scene to serve (`-`: standard input); without it, the built-in default scene.
    pub(crate) scene: Option<PathBuf>,
    /// The address to listen on: 127.0.0.1 (this machine only) unless given, e.g.
    /// 0.0.0.0 to let a room of laptops reach it.
    #[arg(long, value_name = "ADDRESS", default_value = "127.0.0.1")]
    pub(crate) host: IpAddr,
    /// The port to listen on; 0 picks a free one.
    #[arg(long, value_name = "PORT", default_value_t = 8000)]
    pub(crate) port: u16,
    /// Open the page in the default browser.
    #[arg(long)]
    pub(crate) open: bool,
}

/// `viewray serve`: loads the scene once, prints the page's URL as the first line on
/// standard output, and answers requests until Ctrl-C.
pub(crate) fn serve(args: &ServeArgs) -> Result<()> {
    let served = match &args.scene {
        None => ServedScene::parse(
            "the default scene",
            DEFAULT_SCENE.to_owned(),
            Path::new(DEFAULT_SCENE_PATH),
        )?,
        Some(path) if is_standard_stream(path) => {
            let name = Path::new(STDIN_NAME);
            let text = viewray_scene::read_scene_text(std::io::stdin().lock(), name)
                .map_err(scene_error)?;
            ServedScene::parse("standard input", text, name)?
        }
        Some(path) => {
            let text = viewray_scene::read_scene_file(path).map_err(scene_error)?;
            ServedScene::parse(&path.display().to_string(), text, path)?
        }
    };
    let scene_name = served.name().to_owned();
    let server = Server::bind(served, (args.host, args.port), ServeOptions::default())
        .with_context(|| format!("cannot listen on {}:{}", args.host, args.port))?;
    let url = server.url();
    {
        let mut out = std::io::stdout().lock();
        writeln!(out, "{url}")?;
        out.flush()?;
    }
    let stopper = server.stopper();
    ctrlc::set_handler(move || stopper.stop()).context("cannot handle Ctrl-C")?;
    let interactive = std::io::stderr().is_terminal();
    if interactive {
        eprintln!("serving {scene_name} at {url} (Ctrl-C stops)");
        if args.host.is_loopback() {
            eprintln!("only this machine can reach it: --host 0.0.0.0 opens it to the room");
        }
    }
    if args.open {
        open_in_browser(&url);
    }
    server.run().context("the server stopped")?;
    if interactive {
        eprintln!("stopped");
    }
    Ok(())
}

/// Asks the desktop to open `url`; says so on stderr when it cannot.
fn open_in_browser(url: &str) {
    let opener = if cfg!(target_os = "macos") {
        std::process::Command::new("open").arg(url).spawn()
    } else if cfg!(target_os = "windows") {
        std::process::Command::new("cmd")
            .args(["/C", "start", "", url])
            .spawn()
    } else {
        std::process::Command::new("xdg-open").arg(url).spawn()
    };
    if let Err(error) = opener {
        eprintln!("note: cannot open a browser ({error}): open {url} yourself");
    }
}
