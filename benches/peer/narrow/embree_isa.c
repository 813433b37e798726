/* Caps the instruction set of Mitsuba 3's Embree, to imitate a host without AVX-512 on one
   that has it (benches/peer/narrow_peer.py builds and preloads this).

   Mitsuba creates its Embree device with a configuration string of its own; Embree 3 reads
   `max_isa=...` from that string (Embree's "rtcNewDevice" configuration parameters). This
   library interposes Mitsuba's call (its Embree is built in the `mitsuba` namespace, hence
   the C++ name) and appends EMBREE_EXTRA_CONFIG. Python loads extension libraries privately,
   so the real function is looked up in the already loaded EMBREE_LIBRARY, not RTLD_NEXT. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>

typedef void *(*NewDevice)(const char *);

void *_ZN7mitsuba12rtcNewDeviceEPKc(const char *config) {
    const char *path = getenv("EMBREE_LIBRARY");
    void *library = path ? dlopen(path, RTLD_NOW | RTLD_NOLOAD) : NULL;
    NewDevice real = library ? (NewDevice) dlsym(library, "_ZN7mitsuba12rtcNewDeviceEPKc") : NULL;
    if (!real) {
        fprintf(stderr, "embree_isa: Embree's rtcNewDevice not found in EMBREE_LIBRARY\n");
        abort();
    }
    const char *extra = getenv("EMBREE_EXTRA_CONFIG");
    char joined[1024];
    snprintf(joined, sizeof joined, "%s%s%s", config ? config : "",
             (config && *config && extra && *extra) ? "," : "", extra ? extra : "");
    return real(joined);
}
