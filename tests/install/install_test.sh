#!/usr/bin/env bash
# consumer: cmake --install into a temporary prefix, then a project outside
#   Tessera finds it (find_package(Tessera)), links the scene graph, the
#   mediators and a back-end, and renders; a version the package is not refuses.
# deb: cpack makes a .deb holding the programs and the CMake package, with
#   its run-time dependencies.
#   tests/install/install_test.sh consumer|deb BUILD_DIR SOURCE_DIR [SANITIZERS]
# SANITIZERS (the build's TSR_SANITIZE, e.g. address,undefined): the installed
#   libraries are instrumented, so the consumer is built with them too.
set -euo pipefail
mode="$1"
build="$(realpath "$2")"
source="$(realpath "$3")"
sanitize="${4:-}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

if [[ "$mode" == deb ]]; then
  (cd "$work" && cpack --config "$build/CPackConfig.cmake" -B "$work/deb" > "$work/cpack.log") \
    || { cat "$work/cpack.log" >&2; exit 1; }
  deb="$(ls "$work"/deb/*.deb)"
  listing="$(dpkg-deb -c "$deb")"
  for f in ./usr/bin/tessera-render ./usr/bin/tessera-launch ./usr/lib/cmake/Tessera/TesseraConfig.cmake \
           ./usr/include/tsr/sg/scene.hpp; do
    grep -q " $f\$" <<< "$listing" || { echo "install_test: $f not in $(basename "$deb")" >&2; exit 1; }
  done
  depends="$(dpkg-deb -f "$deb" Depends)"
  grep -q "libc6" <<< "$depends" || { echo "install_test: no run-time dependencies found for the .deb: $depends" >&2; exit 1; }
  echo "install_test: $(basename "$deb") ($(du -k "$deb" | cut -f1) KiB) depends on: $depends"
  exit 0
fi
[[ "$mode" == consumer ]] || { echo "install_test: mode consumer or deb, not '$mode'" >&2; exit 2; }

options=()
command -v ccache > /dev/null && options=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
[[ -n "$sanitize" ]] && options+=(-DCMAKE_CXX_FLAGS="-fsanitize=$sanitize" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=$sanitize")

cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
for f in bin/tessera-render bin/tessera-node bin/tessera-launch lib/libtsr_scenegraph.a lib/libtsr_mediator_embree.a \
         include/tsr/sg/scene.hpp include/tsr/med/viewport.hpp lib/cmake/Tessera/TesseraConfig.cmake \
         lib/cmake/Tessera/TesseraConfigVersion.cmake lib/cmake/Tessera/TesseraTargets.cmake \
         share/tessera/configs/stereo-pair.json bin/tessera-cull share/tessera/web/index.html \
         share/tessera/web/node_modules/three/build/three.module.js; do
  [[ -e "$work/prefix/$f" ]] || { echo "install_test: $f not installed" >&2; exit 1; }
done
echo "install_test: installed $(find "$work/prefix" -type f | wc -l) files"

# The installed culling service serves its page and three.js from the
# install, not from the source tree.
"$work/prefix/bin/tessera-cull" builtin:cornell --listen 127.0.0.1:0 --previews 0 > "$work/cull.out" 2> "$work/cull.err" &
cull=$!
for _ in $(seq 200); do grep -q "^listening on " "$work/cull.out" 2>/dev/null && break; sleep 0.05; done
address="$(sed -n 's/^listening on //p' "$work/cull.out")"
page_ok=0
if [[ -n "$address" ]] && curl -sf "http://$address/" | grep -q importmap \
   && curl -sf -o /dev/null "http://$address/three/build/three.module.js"; then page_ok=1; fi
kill "$cull" 2>/dev/null || true
wait "$cull" 2>/dev/null || true
[[ $page_ok == 1 ]] || { echo "install_test: the installed tessera-cull did not serve its page:" >&2; cat "$work/cull.err" >&2; exit 1; }
grep -q "GET / will not work" "$work/cull.err" && { echo "install_test: the installed tessera-cull misses its page" >&2; exit 1; }
"$work/prefix/bin/tessera-cull" --help | grep -qE -- "--web TEXT=$work/prefix/share/tessera/web( |$)" \
  || { echo "install_test: the installed tessera-cull's --web default is not the installed page" >&2; exit 1; }
echo "install_test: the installed tessera-cull serves its page and three.js from share/tessera/web"

cmake -S "$source/tests/install/consumer" -B "$work/consumer" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$work/prefix" "${options[@]}" > "$work/consumer.log" \
  || { cat "$work/consumer.log" >&2; exit 1; }
cmake --build "$work/consumer" > "$work/build.log" || { cat "$work/build.log" >&2; exit 1; }
"$work/consumer/tessera_consumer"

if cmake -S "$source/tests/install/consumer" -B "$work/too-new" -DTSR_WANT_VERSION=9.0 \
     -DCMAKE_PREFIX_PATH="$work/prefix" > "$work/too-new.log" 2>&1; then
  echo "install_test: find_package(Tessera 9.0) succeeded: the version file lets any version through" >&2
  exit 1
fi
grep -q 'compatible with requested version "9.0"' "$work/too-new.log" \
  || { echo "install_test: find_package(Tessera 9.0) failed for another reason:" >&2; cat "$work/too-new.log" >&2; exit 1; }
echo "install_test: find_package(Tessera 9.0) refused, the package is $(grep -o 'version: [0-9.]*' "$work/too-new.log")"

