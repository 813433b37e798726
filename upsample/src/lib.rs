//! prism-upsample: RGB to smooth spectra (Jakob and Hanika 2019). Not built yet; see the
//! project's issue tracker.
