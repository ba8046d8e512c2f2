# SPDX-License-Identifier: Apache-2.0
# Source from bash: point the Python package at the shared build (with the CVODE
# component) of this checkout: build/shared, made by
#   cmake -S . -B build/shared -G Ninja -DCMAKE_BUILD_TYPE=Release -DBUILD_SHARED_LIBS=ON
#   cmake --build build/shared -j2
attack_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)"
export HCIMPACT_LIBRARY="$attack_root/build/shared/libhcimpact.so"
export PYTHONPATH="$attack_root/python${PYTHONPATH:+:$PYTHONPATH}"
