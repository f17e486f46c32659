/* libFuzzer target: the MagicaVoxel reader on arbitrary bytes. It must
 * return 0 or -1 with a message, never crash, read out of bounds or
 * allocate beyond a small multiple of the input. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "vox_read.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    vox_scene s;
    char err[512];
    if (vox_read(data, size, "fuzz.vox", &s, err, sizeof err) == 0) {
        /* what the scene plugin relies on */
        for (int i = 0; i < s.instance_count; i++)
            if (s.instances[i].model < 0 || s.instances[i].model >= s.model_count)
                abort();
        vox_free(&s);
    } else if (!strstr(err, "fuzz.vox"))
        abort();
    return 0;
}
