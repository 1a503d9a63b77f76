#!/usr/bin/env node
// An independent measurement of how an export's instances rest and whether its tile shows, written from
// the definitions in engine/analysis (rest_metrics.h, tiling_metrics.h) without their code: it reads the
// file with glTF-Transform, rebuilds every detail instance's world frame (node world matrix x the
// EXT_mesh_gpu_instancing TRS), places the mesh's collision_spheres extras, and measures
//   hovering = instances that could fall more than 2 cm (straight down, -Y in glTF) before a sphere
//              touches the ground plane y = 0 or a sphere of another instance whose centre is not above;
//   sunk     = instances with a sphere whose bottom lies more than 2 cm below the ground plane y = 0;
//   twins    = instances with a copy of the same mesh, rotation and scale one tile away (tile size from
//              the scene's extras, stats.ghost_tile.tile_size_m).
// Only for scenes without a terrain (the support is the plane). Prints one JSON line:
// {"instances", "hovering", "hovering_fraction", "sunk", "twins", "twin_fraction"}.
//
//   node measure_rest.mjs FILE.glb
import { readFile } from 'node:fs/promises';
import process from 'node:process';

import { NodeIO } from '@gltf-transform/core';
import { ALL_EXTENSIONS } from '@gltf-transform/extensions';

const kThreshold = 0.02;

function mul(m, v) {  // column-major 4x4 times a point
    return [m[0] * v[0] + m[4] * v[1] + m[8] * v[2] + m[12],
            m[1] * v[0] + m[5] * v[1] + m[9] * v[2] + m[13],
            m[2] * v[0] + m[6] * v[1] + m[10] * v[2] + m[14]];
}
function quatRotate(q, v) {  // q = [x, y, z, w]
    const [x, y, z, w] = q;
    const tx = 2 * (y * v[2] - z * v[1]), ty = 2 * (z * v[0] - x * v[2]), tz = 2 * (x * v[1] - y * v[0]);
    return [v[0] + w * tx + (y * tz - z * ty), v[1] + w * ty + (z * tx - x * tz), v[2] + w * tz + (x * ty - y * tx)];
}
function quatMul(a, b) {
    const [ax, ay, az, aw] = a, [bx, by, bz, bw] = b;
    return [aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz];
}
// The rotation of a column-major matrix without scale or shear (the exporter's nodes are rigid).
function matrixQuat(m) {
    const t = m[0] + m[5] + m[10];
    if (t > 0) {
        const s = Math.sqrt(t + 1) * 2;
        return [(m[6] - m[9]) / s, (m[8] - m[2]) / s, (m[1] - m[4]) / s, 0.25 * s];
    }
    if (m[0] > m[5] && m[0] > m[10]) {
        const s = Math.sqrt(1 + m[0] - m[5] - m[10]) * 2;
        return [0.25 * s, (m[4] + m[1]) / s, (m[8] + m[2]) / s, (m[6] - m[9]) / s];
    }
    if (m[5] > m[10]) {
        const s = Math.sqrt(1 + m[5] - m[0] - m[10]) * 2;
        return [(m[4] + m[1]) / s, 0.25 * s, (m[9] + m[6]) / s, (m[8] - m[2]) / s];
    }
    const s = Math.sqrt(1 + m[10] - m[0] - m[5]) * 2;
    return [(m[8] + m[2]) / s, (m[9] + m[6]) / s, 0.25 * s, (m[1] - m[4]) / s];
}

function instancesOf(document) {
    const out = [];
    for (const node of document.getRoot().listNodes()) {
        const mesh = node.getMesh();
        const spheres = mesh && (mesh.getExtras() || {}).collision_spheres;
        if (!Array.isArray(spheres)) continue;
        const world = node.getWorldMatrix();
        const nodeQuat = matrixQuat(world);
        const inst = node.getExtension('EXT_mesh_gpu_instancing');
        const count = inst ? inst.getAttribute('TRANSLATION').getCount() : 1;
        for (let i = 0; i < count; ++i) {
            const t = inst ? inst.getAttribute('TRANSLATION').getElement(i, []) : [0, 0, 0];
            const r = inst && inst.getAttribute('ROTATION') ? inst.getAttribute('ROTATION').getElement(i, []) : [0, 0, 0, 1];
            const s = inst && inst.getAttribute('SCALE') ? inst.getAttribute('SCALE').getElement(i, []) : [1, 1, 1];
            const toWorld = (p) => mul(world, [t[0] + s[0] * quatRotate(r, p)[0], t[1] + s[1] * quatRotate(r, p)[1],
                                               t[2] + s[2] * quatRotate(r, p)[2]]);
            out.push({ mesh, position: toWorld([0, 0, 0]), rotation: quatMul(nodeQuat, r), scale: s[0],
                       spheres: spheres.map(([x, y, z, radius]) => ({ c: toWorld([x, y, z]), r: radius * s[0] })) });
        }
    }
    return out;
}

// Only a sphere whose centre lies at most kThreshold + 2·maxR below a's can hold a within kThreshold of its
// place, so a 3D grid searched over that band counts exactly what an all-pairs search would count (the
// stone hut's walls stack hundreds of spheres over one ground cell; a search of whole columns took minutes).
function hovering(instances) {
    const all = [];
    instances.forEach((inst, owner) => inst.spheres.forEach((s) => all.push({ ...s, owner })));
    const maxR = all.reduce((m, s) => Math.max(m, s.r), 0);
    const cell = Math.max(2 * maxR, 1e-6);
    const grid = new Map();
    const index = (v) => Math.floor(v / cell);
    const key = (x, y, z) => `${x},${y},${z}`;
    for (const s of all) {
        const k = key(index(s.c[0]), index(s.c[1]), index(s.c[2]));
        if (!grid.has(k)) grid.set(k, []);
        grid.get(k).push(s);
    }
    let count = 0;
    instances.forEach((inst, owner) => {
        let drop = Infinity;
        for (const a of inst.spheres) {
            drop = Math.min(drop, Math.max(0, a.c[1] - a.r));
            const cx = index(a.c[0]), cz = index(a.c[2]);
            const yLow = index(a.c[1] - 2 * maxR - kThreshold), yHigh = index(a.c[1]);
            for (let cy = yLow; cy <= yHigh; ++cy)
                for (let dx = -1; dx <= 1; ++dx)
                    for (let dz = -1; dz <= 1; ++dz)
                        for (const b of grid.get(key(cx + dx, cy, cz + dz)) || []) {
                            if (b.owner === owner || b.c[1] > a.c[1]) continue;
                            const reach = a.r + b.r;
                            const h2 = (a.c[0] - b.c[0]) ** 2 + (a.c[2] - b.c[2]) ** 2;
                            if (h2 >= reach * reach) continue;
                            drop = Math.min(drop, Math.max(0, a.c[1] - b.c[1] - Math.sqrt(reach * reach - h2)));
                        }
        }
        if (drop > kThreshold) ++count;
    });
    return count;
}

function sunk(instances) {
    return instances.filter((inst) => inst.spheres.some((s) => -(s.c[1] - s.r) > kThreshold)).length;
}

function twins(instances, tile) {
    const meshIds = new Map();
    const frame = (inst) => {
        if (!meshIds.has(inst.mesh)) meshIds.set(inst.mesh, meshIds.size);
        let q = inst.rotation;
        if (q[3] < 0) q = q.map((v) => -v);
        return [meshIds.get(inst.mesh), ...q.map((v) => Math.round(v * 1e4)), Math.round(inst.scale * 1e4)].join(',');
    };
    const here = new Set(instances.map((inst) => `${frame(inst)}|${inst.position.map((v) => Math.round(v * 1e3)).join(',')}`));
    let count = 0;
    for (const inst of instances) {
        const f = frame(inst);
        let found = false;
        for (let v = 0; v < 27 && !found; ++v) {
            if (v === 13) continue;
            const d = [Math.floor(v / 9) - 1, Math.floor(v / 3) % 3 - 1, v % 3 - 1];
            // Rounding noise is ~1e-6 m; look on both sides of a millimetre boundary.
            const options = inst.position.map((p, a) => {
                const r = (p + tile * d[a]) * 1e3;
                const base = Math.round(r);
                return Math.abs(r - Math.floor(r) - 0.5) < 0.01 ? [base, r - Math.floor(r) < 0.5 ? base + 1 : base - 1] : [base];
            });
            for (const x of options[0]) for (const y of options[1]) for (const z of options[2])
                if (here.has(`${f}|${x},${y},${z}`)) found = true;
        }
        if (found) ++count;
    }
    return count;
}

async function main() {
    const file = process.argv[2];
    if (!file) {
        console.error('usage: node measure_rest.mjs FILE.glb');
        process.exit(2);
    }
    const io = new NodeIO().registerExtensions(ALL_EXTENSIONS);
    const document = await io.readBinary(new Uint8Array(await readFile(file)));
    const extras = document.getRoot().listScenes()[0]?.getExtras() || {};
    const stats = extras.stats || extras;
    const tile = stats?.ghost_tile?.tile_size_m;
    if (!(tile > 0)) throw new Error(`${file}: no ghost_tile.tile_size_m in the scene's extras`);
    const instances = instancesOf(document);
    const h = hovering(instances);
    const t = twins(instances, tile);
    console.log(JSON.stringify({ instances: instances.length, hovering: h, hovering_fraction: h / instances.length,
                                 sunk: sunk(instances), twins: t, twin_fraction: t / instances.length }));
}

main().catch((e) => {
    console.error(`measure_rest: ${e.stack || e}`);
    process.exit(1);
});
