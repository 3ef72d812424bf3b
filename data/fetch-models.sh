#!/usr/bin/env bash
# Fetch well-known public test models from Debian's libcgal-demo package (CGAL 5.5 demo data)
# into data/models/ (git-ignored). Idempotent: does nothing when every model is already there.
#
#   data/fetch-models.sh            # into data/models/ next to this script
#   data/fetch-models.sh DIR        # into DIR
#
# Needs apt-get and dpkg-deb (Debian/Ubuntu). `apt-get download` needs no root; `apt-get update`
# (run only when the package is not in the local lists) needs root or sudo.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
dest="${1:-$here/models}"
package=libcgal-demo
# Paths inside the package's data.tar.gz, below its top folder.
wanted=(
  meshes/armadillo.off
  meshes/bunny00.off
  meshes/elephant.off
  meshes/ChineseDragon-10kv.off
  meshes/man.off
  meshes/homer.off
  points_3/kitten.xyz
  points_3/sphere_20k.xyz
  points_3/hippo1.ply
)

missing=0
for path in "${wanted[@]}"; do
  [ -s "$dest/$(basename "$path")" ] || missing=$((missing + 1))
done
if [ "$missing" -eq 0 ]; then
  echo "fetch-models: all ${#wanted[@]} models already in $dest"
  exit 0
fi

for tool in apt-get dpkg-deb tar; do
  command -v "$tool" >/dev/null || { echo "fetch-models: error: $tool not found (Debian/Ubuntu needed)" >&2; exit 1; }
done
sudo_cmd=()
if [ "$(id -u)" -ne 0 ] && command -v sudo >/dev/null; then sudo_cmd=(sudo); fi
apt_opts=()
# As root, apt drops to the _apt user for downloads, which cannot write to our private temp dir.
if [ "$(id -u)" -eq 0 ]; then apt_opts=(-o APT::Sandbox::User=root); fi

tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"

if ! apt-get "${apt_opts[@]}" download "$package" >/dev/null 2>&1; then
  echo "fetch-models: $package not in the package lists, running apt-get update" >&2
  "${sudo_cmd[@]}" apt-get update -qq
  apt-get "${apt_opts[@]}" download "$package" >/dev/null
fi
deb="$(ls ./"$package"_*.deb | head -n 1)"

# The demo data is a tarball inside the package (usr/share/doc/libcgal-dev/data.tar.gz in
# CGAL 5.5's Debian package); look it up rather than trusting the path.
inner="$(dpkg-deb -c "$deb" | awk '{print $NF}' | grep -E '/data\.tar\.gz$' | head -n 1 || true)"
if [ -z "$inner" ]; then
  echo "fetch-models: error: no data.tar.gz in $deb; its layout changed:" >&2
  dpkg-deb -c "$deb" | head -n 20 >&2
  exit 1
fi
dpkg-deb --fsys-tarfile "$deb" | tar -xO "$inner" >data.tar.gz
tar -tzf data.tar.gz >members.txt

mkdir -p "$dest"
found=0
for path in "${wanted[@]}"; do
  member="$(grep -E "(^|/)${path//./\\.}\$" members.txt | head -n 1 || true)"
  if [ -z "$member" ]; then
    echo "fetch-models: not in $package: $path" >&2
    continue
  fi
  tar -xzOf data.tar.gz "$member" >"$dest/$(basename "$path").part"
  mv "$dest/$(basename "$path").part" "$dest/$(basename "$path")"
  found=$((found + 1))
done

echo "fetch-models: $found of ${#wanted[@]} models from $(basename "$deb") in $dest:"
for path in "${wanted[@]}"; do
  f="$dest/$(basename "$path")"
  [ -s "$f" ] && printf '  %-24s %10d bytes\n' "$(basename "$path")" "$(stat -c %s "$f")"
done
[ "$found" -gt 0 ]
