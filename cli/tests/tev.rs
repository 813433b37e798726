//! `--tev`: a server on loopback that speaks tev's protocol (the packets of tev's
//! `Ipc.cpp`: a u32 length, a type byte, then the fields) receives the close, create and
//! update packets of a render with the right size, channels and pixels; a viewer that is
//! not there, or that hangs up mid-render, is one warning and the render goes on.

mod common;

use std::io::Read;
use std::net::TcpListener;
use std::thread;

use common::{assert_success, prism, temp_dir};

/// One packet as tev reads it.
#[derive(Debug)]
enum Packet {
    Close {
        name: String,
    },
    Create {
        name: String,
        width: u32,
        height: u32,
        channels: Vec<String>,
    },
    Update {
        name: String,
        channels: Vec<String>,
        x: u32,
        y: u32,
        width: u32,
        height: u32,
        planes: Vec<Vec<f32>>,
    },
}

struct Reader<'a>(&'a [u8]);

impl Reader<'_> {
    fn u8(&mut self) -> u8 {
        let v = self.0[0];
        self.0 = &self.0[1..];
        v
    }
    fn u32(&mut self) -> u32 {
        let v = u32::from_le_bytes(self.0[..4].try_into().unwrap());
        self.0 = &self.0[4..];
        v
    }
    fn u64(&mut self) -> u64 {
        let v = u64::from_le_bytes(self.0[..8].try_into().unwrap());
        self.0 = &self.0[8..];
        v
    }
    fn f32(&mut self) -> f32 {
        f32::from_bits(self.u32())
    }
    fn string(&mut self) -> String {
        let end = self
            .0
            .iter()
            .position(|&b| b == 0)
            .expect("a NUL-terminated string");
        let s = String::from_utf8(self.0[..end].to_vec()).unwrap();
        self.0 = &self.0[end + 1..];
        s
    }
}

/// The packets in `bytes`, each checked to fill its length exactly.
fn packets(mut bytes: &[u8]) -> Vec<Packet> {
    let mut out = Vec::new();
    while !bytes.is_empty() {
        let length = u32::from_le_bytes(bytes[..4].try_into().unwrap()) as usize;
        let mut r = Reader(&bytes[4..length]);
        let packet = match r.u8() {
            2 => Packet::Close { name: r.string() },
            4 => {
                let _focus = r.u8();
                let name = r.string();
                let (width, height, n) = (r.u32(), r.u32(), r.u32());
                let channels = (0..n).map(|_| r.string()).collect();
                Packet::Create {
                    name,
                    width,
                    height,
                    channels,
                }
            }
            6 => {
                let _focus = r.u8();
                let name = r.string();
                let n = r.u32() as usize;
                let channels: Vec<String> = (0..n).map(|_| r.string()).collect();
                let (x, y, width, height) = (r.u32(), r.u32(), r.u32(), r.u32());
                let offsets: Vec<u64> = (0..n).map(|_| r.u64()).collect();
                let strides: Vec<u64> = (0..n).map(|_| r.u64()).collect();
                let mut data = Vec::new();
                while !r.0.is_empty() {
                    data.push(r.f32());
                }
                let pixels = (width * height) as u64;
                let planes = (0..n)
                    .map(|k| {
                        (0..pixels)
                            .map(|i| data[(offsets[k] + i * strides[k]) as usize])
                            .collect()
                    })
                    .collect();
                Packet::Update {
                    name,
                    channels,
                    x,
                    y,
                    width,
                    height,
                    planes,
                }
            }
            other => panic!("unexpected packet type {other}"),
        };
        assert!(r.0.is_empty(), "{packet:?} left bytes");
        out.push(packet);
        bytes = &bytes[length..];
    }
    out
}

/// A one-connection server: everything it receives (up to `limit` bytes, then it hangs
/// up).
fn server(limit: usize) -> (String, thread::JoinHandle<Vec<u8>>) {
    let listener = TcpListener::bind("127.0.0.1:0").unwrap();
    let address = listener.local_addr().unwrap().to_string();
    let handle = thread::spawn(move || {
        let (mut socket, _) = listener.accept().unwrap();
        let mut bytes = Vec::new();
        let mut buffer = [0u8; 65536];
        while bytes.len() < limit {
            match socket.read(&mut buffer) {
                Ok(0) | Err(_) => break,
                Ok(n) => bytes.extend_from_slice(&buffer[..n]),
            }
        }
        bytes
    });
    (address, handle)
}

#[test]
fn a_viewer_receives_the_image_and_its_aovs() {
    let dir = temp_dir("tev");
    let exr = dir.join("out.exr");
    let (address, server) = server(usize::MAX);
    let out = prism(&[
        "render",
        "--spp",
        "3",
        "--width",
        "20",
        "--height",
        "14",
        "-q",
        "--aov",
        "albedo,depth",
        "--tev",
        &address,
        "-o",
        exr.to_str().unwrap(),
    ]);
    assert_success(&out);
    assert!(
        out.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let packets = packets(&server.join().unwrap());
    let channels = [
        "R", "G", "B", "A", "albedo.R", "albedo.G", "albedo.B", "depth.Z",
    ];
    match &packets[..2] {
        [
            Packet::Close { name: a },
            Packet::Create {
                name: b,
                width: 20,
                height: 14,
                channels: c,
            },
        ] => {
            assert_eq!(a, "prism: effects");
            assert_eq!(a, b);
            assert_eq!(c, &channels);
        }
        other => panic!("{other:?}"),
    }
    // Every update covers the image with the created channels; the last one holds the
    // image the EXR holds.
    let updates: Vec<&Packet> = packets[2..].iter().collect();
    assert!(!updates.is_empty());
    let Packet::Update {
        name,
        channels: c,
        x: 0,
        y: 0,
        width: 20,
        height: 14,
        planes,
    } = updates[updates.len() - 1]
    else {
        panic!("{:?}", updates.last());
    };
    assert_eq!(name, "prism: effects");
    assert_eq!(c, &channels);
    let image = prism_integrator::decode_exr(&std::fs::read(&exr).unwrap()).unwrap();
    for (k, channel) in channels.iter().enumerate() {
        let (_, values) = image.channels.iter().find(|(n, _)| n == channel).unwrap();
        assert_eq!(&planes[k], values, "{channel}");
    }
}

#[test]
fn a_missing_or_vanishing_viewer_is_one_warning() {
    let dir = temp_dir("tev-gone");
    let exr = dir.join("out.exr");
    // Nothing listens on a port just freed.
    let free = TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .to_string();
    let out = prism(&[
        "render",
        "--spp",
        "2",
        "--width",
        "16",
        "--height",
        "12",
        "-q",
        "--tev",
        &free,
        "-o",
        exr.to_str().unwrap(),
    ]);
    assert_success(&out);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains("no tev viewer") && stderr.contains(&free),
        "{stderr}"
    );
    assert!(exr.exists());
    // A viewer that hangs up after the first bytes: the render finishes, warned once.
    let (address, server) = server(1);
    let out = prism(&[
        "render",
        "--spp",
        "40",
        "--width",
        "256",
        "--height",
        "192",
        "-q",
        "--tev",
        &address,
        "-o",
        exr.to_str().unwrap(),
    ]);
    server.join().unwrap();
    assert_success(&out);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.lines().count() <= 1 && !stderr.contains("panicked"),
        "{stderr}"
    );
}
