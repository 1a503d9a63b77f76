#!/usr/bin/env node
// What an export instantiates, as one number: prints "<instances> <hash>" where the hash (SHA-256,
// first 16 hex digits) covers every node's name and translation and every EXT_mesh_gpu_instancing
// TRANSLATION, ROTATION and SCALE array, read by glTF-Transform. Two exports of the same instances hash
// the same whatever their materials, textures or meshes (run_material_checks.sh relies on it).
//
//   node instance_hash.mjs FILE.glb|FILE.gltf
import crypto from 'node:crypto';
import process from 'node:process';

import { NodeIO } from '@gltf-transform/core';
import { ALL_EXTENSIONS } from '@gltf-transform/extensions';

const file = process.argv[2];
if (!file) {
    console.error('usage: node instance_hash.mjs FILE');
    process.exit(2);
}
const document = await new NodeIO().registerExtensions(ALL_EXTENSIONS).read(file);
const hash = crypto.createHash('sha256');
let instances = 0;
for (const node of document.getRoot().listNodes()) {
    hash.update(`${node.getName()} ${JSON.stringify(node.getTranslation())}\n`);
    const ext = node.getExtension('EXT_mesh_gpu_instancing');
    if (!ext) continue;
    for (const semantic of ['TRANSLATION', 'ROTATION', 'SCALE']) {
        const array = ext.getAttribute(semantic).getArray();
        hash.update(Buffer.from(array.buffer, array.byteOffset, array.byteLength));
    }
    instances += ext.getAttribute('TRANSLATION').getCount();
}
console.log(`${instances} ${hash.digest('hex').slice(0, 16)}`);
