//! Intel Open Image Denoise 2.x, loaded at run time through its C API (`oidn.h`): the
//! device, the "RT" filter and its images, nothing else. Loading at run time keeps the
//! build free of it: a prism without the library installed renders as ever, and
//! `--denoise` says in one line what to install.
//!
//! The only unsafe code of the CLI: calls into the library, with pointers to buffers this
//! module owns for the duration of each call (OIDN's shared images read and write them
//! only inside `oidnExecuteFilter`).
#![allow(unsafe_code)]

use std::ffi::{CStr, CString, c_char, c_int, c_void};
use std::path::{Path, PathBuf};

use libloading::Library;

type Device = *mut c_void;
type Filter = *mut c_void;

/// OIDN_DEVICE_TYPE_CPU: the CPU device, which every build of the library has.
const DEVICE_CPU: c_int = 1;
/// OIDN_FORMAT_FLOAT3.
const FORMAT_FLOAT3: c_int = 3;
/// OIDN_QUALITY_HIGH (for final frames).
const QUALITY_HIGH: c_int = 6;

/// The library's file name on this system (the major version is the ABI's).
#[cfg(target_os = "linux")]
pub const LIBRARY: &str = "libOpenImageDenoise.so.2";
#[cfg(target_os = "macos")]
pub const LIBRARY: &str = "libOpenImageDenoise.2.dylib";
#[cfg(windows)]
pub const LIBRARY: &str = "OpenImageDenoise.dll";
#[cfg(not(any(target_os = "linux", target_os = "macos", windows)))]
pub const LIBRARY: &str = "libOpenImageDenoise.so.2";

/// The functions of the C API prism calls.
struct Api {
    new_device: unsafe extern "C" fn(c_int) -> Device,
    commit_device: unsafe extern "C" fn(Device),
    release_device: unsafe extern "C" fn(Device),
    device_error: unsafe extern "C" fn(Device, *mut *const c_char) -> c_int,
    new_filter: unsafe extern "C" fn(Device, *const c_char) -> Filter,
    set_shared_image: unsafe extern "C" fn(
        Filter,
        *const c_char,
        *mut c_void,
        c_int,
        usize,
        usize,
        usize,
        usize,
        usize,
    ),
    set_bool: unsafe extern "C" fn(Filter, *const c_char, bool),
    set_int: unsafe extern "C" fn(Filter, *const c_char, c_int),
    commit_filter: unsafe extern "C" fn(Filter),
    execute_filter: unsafe extern "C" fn(Filter),
    release_filter: unsafe extern "C" fn(Filter),
}

/// A loaded library and its CPU device.
pub struct Oidn {
    api: Api,
    device: Device,
    /// Where the library was loaded from.
    pub path: PathBuf,
    // Kept last: dropped after the device is released.
    _library: Library,
}

/// An RGB image, three f32 per pixel, row-major.
pub type Image = Vec<[f32; 3]>;

impl Oidn {
    /// Loads the library at `path` (a file name alone searches the system's paths) and
    /// creates its CPU device.
    pub fn load(path: &Path) -> Result<Self, String> {
        let fail = |what: String| format!("Open Image Denoise at '{}': {what}", path.display());
        // SAFETY: loading runs the library's initializers; OIDN's only set up its own state.
        let library = unsafe { Library::new(path) }.map_err(|e| fail(e.to_string()))?;
        macro_rules! symbol {
            ($name:literal) => {
                // SAFETY: the signature is the one oidn.h (2.x) declares for this name.
                *unsafe { library.get(concat!($name, "\0").as_bytes()) }
                    .map_err(|e| fail(format!("no {}: {e}", $name)))?
            };
        }
        let api = Api {
            new_device: symbol!("oidnNewDevice"),
            commit_device: symbol!("oidnCommitDevice"),
            release_device: symbol!("oidnReleaseDevice"),
            device_error: symbol!("oidnGetDeviceError"),
            new_filter: symbol!("oidnNewFilter"),
            set_shared_image: symbol!("oidnSetSharedFilterImage"),
            set_bool: symbol!("oidnSetFilterBool"),
            set_int: symbol!("oidnSetFilterInt"),
            commit_filter: symbol!("oidnCommitFilter"),
            execute_filter: symbol!("oidnExecuteFilter"),
            release_filter: symbol!("oidnReleaseFilter"),
        };
        // SAFETY: plain calls with a valid device type; a null device is checked.
        let device = unsafe { (api.new_device)(DEVICE_CPU) };
        if device.is_null() {
            return Err(fail("it could not create a CPU device".into()));
        }
        let oidn = Oidn {
            api,
            device,
            path: path.to_path_buf(),
            _library: library,
        };
        // SAFETY: the device is valid.
        unsafe { (oidn.api.commit_device)(oidn.device) };
        oidn.check().map_err(fail)?;
        Ok(oidn)
    }

    /// Whether the library at `path` (or found by the system under that name) loads.
    pub fn loadable(path: &Path) -> bool {
        // SAFETY: as in `load`; the library is unloaded again at once.
        unsafe { Library::new(path) }.is_ok()
    }

    /// The device's pending error, if any (which clears it).
    fn check(&self) -> Result<(), String> {
        let mut message: *const c_char = std::ptr::null();
        // SAFETY: the device is valid; the message, when set, is a C string the library
        // owns until its next call.
        let code = unsafe { (self.api.device_error)(self.device, &mut message) };
        if code == 0 {
            return Ok(());
        }
        let text = if message.is_null() {
            String::new()
        } else {
            // SAFETY: non-null, NUL-terminated, valid until the next call into the device.
            unsafe { CStr::from_ptr(message) }
                .to_string_lossy()
                .into_owned()
        };
        Err(format!("error {code}: {text}"))
    }

    /// Runs one "RT" filter over `width` x `height` images `inputs` by name (`color`,
    /// `albedo`, `normal`), with boolean parameters `flags` (`hdr`, `cleanAux`); returns
    /// its output.
    pub fn filter(
        &self,
        width: usize,
        height: usize,
        inputs: &[(&str, &Image)],
        flags: &[(&str, bool)],
    ) -> Result<Image, String> {
        let pixels = width * height;
        if pixels == 0 || inputs.iter().any(|(_, image)| image.len() != pixels) {
            return Err("images of the wrong size".into());
        }
        let mut output: Image = vec![[0.0; 3]; pixels];
        let name = |s: &str| CString::new(s).map_err(|_| format!("bad name {s}"));
        // SAFETY: the device is valid; "RT" is a filter type of every OIDN 2.x.
        let filter = unsafe { (self.api.new_filter)(self.device, name("RT")?.as_ptr()) };
        if filter.is_null() {
            self.check()?;
            return Err("no RT filter".into());
        }
        let mut run = || -> Result<(), String> {
            let set_image = |key: &str, data: *mut c_void| -> Result<(), String> {
                let key = name(key)?;
                // SAFETY: `data` points at `pixels` packed [f32; 3] that stay alive and
                // unmoved until this function returns, after the filter has executed;
                // OIDN only reads the inputs.
                unsafe {
                    (self.api.set_shared_image)(
                        filter,
                        key.as_ptr(),
                        data,
                        FORMAT_FLOAT3,
                        width,
                        height,
                        0,
                        12,
                        12 * width,
                    )
                };
                Ok(())
            };
            for (key, image) in inputs {
                set_image(key, image.as_ptr().cast_mut().cast())?;
            }
            set_image("output", output.as_mut_ptr().cast())?;
            for (key, value) in flags {
                let key = name(key)?;
                // SAFETY: a valid filter and a NUL-terminated parameter name.
                unsafe { (self.api.set_bool)(filter, key.as_ptr(), *value) };
            }
            let quality = name("quality")?;
            // SAFETY: as above.
            unsafe {
                (self.api.set_int)(filter, quality.as_ptr(), QUALITY_HIGH);
                (self.api.commit_filter)(filter);
            }
            self.check()?;
            // SAFETY: every image set is alive and of the size given (checked above).
            unsafe { (self.api.execute_filter)(filter) };
            self.check()
        };
        let result = run();
        // SAFETY: the filter was created above and is released once.
        unsafe { (self.api.release_filter)(filter) };
        result.map(|()| output)
    }
}

impl Drop for Oidn {
    fn drop(&mut self) {
        // SAFETY: the device was created by `load` and is released once.
        unsafe { (self.api.release_device)(self.device) };
    }
}
