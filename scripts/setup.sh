#!/usr/bin/env bash
# Installs everything voxrg needs on a fresh Debian 12 (bookworm) machine.
# Idempotent: safe to run again; it only installs what is missing.
# Mesa's lavapipe comes from bookworm-backports (Mesa >= 24 has VK_KHR_ray_query);
# if that fails we keep Debian main's Mesa and voxrg runs with DDA traversal only.
# libssl-dev: OpenSSL's libcrypto, SHA-256 for compare's reference cache keys.
# libopenexr-dev: OpenEXR, the file format for float images: `render --dump`
# writes images as EXR (halves and floats as stored, NaN and Inf kept, uint
# channels as integers), which PNG cannot hold.
# slurm-wlm and munge: the compare_slurm test runs compare on a one-node Slurm
# cluster it starts itself (voxrg builds and runs without them).
set -u
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive

PKGS="build-essential cmake pkg-config git ca-certificates
      libvulkan-dev vulkan-validationlayers vulkan-tools spirv-tools
      glslang-dev glslang-tools libspirv-cross-c-shared-dev libglfw3-dev libinih-dev libspng-dev libopenexr-dev libjemalloc-dev
      xvfb xauth xdotool chromium clang llvm libclang-rt-14-dev python3
      libssl-dev slurm-wlm munge"

missing=""
for p in $PKGS mesa-vulkan-drivers; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done

have_backports() {
    grep -rqs "bookworm-backports" /etc/apt/sources.list /etc/apt/sources.list.d/
}
lavapipe_new_enough() {
    v=$(dpkg-query -W -f='${Version}' mesa-vulkan-drivers 2>/dev/null) || return 1
    dpkg --compare-versions "$v" ge 24 2>/dev/null
}

if [ -z "$missing" ] && lavapipe_new_enough; then
    echo "setup: all dependencies present"
    exit 0
fi

if ! have_backports; then
    echo "setup: enabling bookworm-backports"
    printf 'Types: deb\nURIs: http://deb.debian.org/debian\nSuites: bookworm-backports\nComponents: main\nSigned-By: /usr/share/keyrings/debian-archive-keyring.gpg\n' |
        $SUDO tee /etc/apt/sources.list.d/voxrg-backports.sources >/dev/null
fi
$SUDO apt-get update -qq || echo "setup: apt-get update reported errors (continuing)"
# shellcheck disable=SC2086
$SUDO apt-get install -y -qq --no-install-recommends $PKGS || { echo "setup: failed to install base packages" >&2; exit 1; }

if $SUDO apt-get install -y -qq --no-install-recommends -t bookworm-backports mesa-vulkan-drivers; then
    :
else
    echo "setup: Mesa from bookworm-backports unavailable; installing Debian main's lavapipe" >&2
    $SUDO apt-get install -y -qq --no-install-recommends mesa-vulkan-drivers || { echo "setup: no lavapipe" >&2; exit 1; }
fi
if ! lavapipe_new_enough; then
    echo "setup: NOTE lavapipe is older than Mesa 24: no VK_KHR_ray_query; voxrg will use DDA traversal only"
fi
echo "setup: done"
