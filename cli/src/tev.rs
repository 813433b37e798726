//! A live view of a render in the tev image viewer (github.com/Tom94/tev) over its TCP
//! protocol, as pbrt-v4's `--display-server` streams to it: the image is created on the
//! first pass (an older one of the same name closed first, so a second render replaces
//! it), updated every few seconds and at the end, its channels the radiance (R, G, B, A)
//! and any AOVs. The packets are `tev_client`'s; a viewer that is not listening, or that
//! goes away, is one warning line and the render goes on.

use std::net::{TcpStream, ToSocketAddrs};
use std::time::{Duration, Instant};

use prism_integrator::Film;
use prism_spectrum::color::RgbSpaceId;
use tev_client::{PacketCloseImage, PacketCreateImage, PacketUpdateImage, TevClient};

/// tev's port unless HOST:PORT says otherwise.
pub const DEFAULT_PORT: u16 = 14158;

/// How often the image is sent while the render runs.
const EVERY: Duration = Duration::from_secs(2);

/// Floats per update packet at most (4 MiB): a large image goes as bands of rows.
const PACKET_FLOATS: usize = 1 << 20;

/// A render's stream to tev.
pub struct TevPreview {
    client: Option<TevClient>,
    address: String,
    name: String,
    space: RgbSpaceId,
    created: bool,
    last: Option<Instant>,
}

/// `HOST` or `HOST:PORT` (an IPv6 host in brackets when a port follows).
pub fn address(spec: &str) -> Result<String, String> {
    let spec = spec.trim();
    if spec.is_empty() {
        return Err("--tev needs HOST[:PORT]".into());
    }
    let has_port = match spec.rsplit_once(':') {
        Some((host, port)) if !host.is_empty() && (!host.contains(':') || host.ends_with(']')) => {
            port.parse::<u16>()
                .map_err(|_| format!("--tev {spec}: '{port}' is not a port"))?;
            true
        }
        _ => false,
    };
    Ok(if has_port {
        spec.to_string()
    } else if spec.contains(':') && !spec.starts_with('[') {
        format!("[{spec}]:{DEFAULT_PORT}")
    } else {
        format!("{spec}:{DEFAULT_PORT}")
    })
}

impl TevPreview {
    /// Connects to tev at `address` (HOST:PORT) for an image called `name`, its colours in
    /// `space`; a warning, and no stream, where nothing answers.
    pub fn connect(address: &str, name: &str, space: RgbSpaceId) -> Self {
        let client = match connect(address) {
            Ok(socket) => Some(TevClient::wrap(socket)),
            Err(e) => {
                eprintln!(
                    "prism: warning: no tev viewer at {address} ({e}); rendering without the live view"
                );
                None
            }
        };
        Self {
            client,
            address: address.to_string(),
            name: name.to_string(),
            space,
            created: false,
            last: None,
        }
    }

    /// Sends `film` if the last send was long enough ago, or `always` (the end).
    pub fn show(&mut self, film: &Film, always: bool) {
        if self.client.is_none() || film.samples() == 0 {
            return;
        }
        if !always && self.last.is_some_and(|t| t.elapsed() < EVERY) {
            return;
        }
        self.last = Some(Instant::now());
        if let Err(e) = self.send(film) {
            eprintln!(
                "prism: warning: the tev viewer at {} went away ({e}); the render goes on",
                self.address
            );
            self.client = None;
        }
    }

    fn send(&mut self, film: &Film) -> std::io::Result<()> {
        let Some(client) = self.client.as_mut() else {
            return Ok(());
        };
        let channels = channels(film, self.space);
        let names: Vec<&str> = channels.iter().map(|(n, _)| n.as_str()).collect();
        let (width, height) = (film.width(), film.height());
        if !self.created {
            client.send(PacketCloseImage {
                image_name: &self.name,
            })?;
            client.send(PacketCreateImage {
                image_name: &self.name,
                grab_focus: true,
                width,
                height,
                channel_names: &names,
            })?;
            self.created = true;
        }
        let w = width as usize;
        let rows = (PACKET_FLOATS / (w * names.len()).max(1)).max(1);
        for y0 in (0..height as usize).step_by(rows) {
            let y1 = (y0 + rows).min(height as usize);
            let pixels = (y1 - y0) * w;
            // Channel after channel, each the band's pixels in order.
            let mut data = Vec::with_capacity(pixels * names.len());
            for (_, values) in &channels {
                data.extend_from_slice(&values[y0 * w..y1 * w]);
            }
            let offsets: Vec<u64> = (0..names.len()).map(|k| (k * pixels) as u64).collect();
            let strides = vec![1u64; names.len()];
            client.send(PacketUpdateImage {
                image_name: &self.name,
                grab_focus: false,
                channel_names: &names,
                channel_offsets: &offsets,
                channel_strides: &strides,
                x: 0,
                y: y0 as u32,
                width,
                height: (y1 - y0) as u32,
                data: &data,
            })?;
        }
        Ok(())
    }
}

/// The channels tev shows: R, G, B, A, then the AOVs' layers.
fn channels(film: &Film, space: RgbSpaceId) -> Vec<(String, Vec<f32>)> {
    let space = space.space();
    let rgb = film.to_rgb(space);
    let mut out: Vec<(String, Vec<f32>)> = ["R", "G", "B"]
        .iter()
        .enumerate()
        .map(|(k, n)| (n.to_string(), rgb.iter().map(|p| p[k]).collect()))
        .collect();
    out.push(("A".into(), film.alphas()));
    out.extend(film.aov_images(space));
    out
}

fn connect(address: &str) -> std::io::Result<TcpStream> {
    let mut last = std::io::Error::other("the address resolves to nothing");
    for addr in address.to_socket_addrs()? {
        match TcpStream::connect_timeout(&addr, Duration::from_secs(2)) {
            Ok(socket) => {
                socket.set_write_timeout(Some(Duration::from_secs(10)))?;
                socket.set_nodelay(true)?;
                return Ok(socket);
            }
            Err(e) => last = e,
        }
    }
    Err(last)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn addresses() {
        assert_eq!(address("localhost").unwrap(), "localhost:14158");
        assert_eq!(address("127.0.0.1:9000").unwrap(), "127.0.0.1:9000");
        assert_eq!(address("::1").unwrap(), "[::1]:14158");
        assert_eq!(address("[::1]:9000").unwrap(), "[::1]:9000");
        assert!(address("host:port").unwrap_err().contains("not a port"));
        assert!(address(" ").is_err());
    }
}
