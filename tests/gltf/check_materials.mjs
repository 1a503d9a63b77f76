// Material checks for check_gltf.mjs (issue 10): what glTF-Transform read back of every material's
// baseColorTexture, with the PNG decoded here (zlib from Node, the filters undone) rather than trusted
// from its header.
//
//   checkMaterials(document, problems) -> {materials, textured_materials, images, cutout_materials}
// For every material with a baseColorTexture:
//   - the image is image/png, decodes (8-bit RGB or RGBA, every scanline filter valid, the inflated size
//     exact) to the size glTF-Transform reports, and has at least one pixel;
//   - the texture info uses texCoord 0 and the sampler repeats in both directions (the textures tile);
//   - every primitive using the material has TEXCOORD_0 (VEC2, as many as POSITION);
//   - alphaMode MASK exactly when the decoded alpha has a pixel below 128 (a cut-out texture is drawn
//     as one, an opaque one is not).
// Problems are appended to `problems` as sentences naming the material.
import zlib from 'node:zlib';

const kRepeat = 10497;

// Decodes an 8-bit RGB or RGBA PNG: {width, height, channels, pixels (Uint8Array)} or throws.
export function decodePng(bytes) {
    const b = Buffer.from(bytes);
    const signature = [137, 80, 78, 71, 13, 10, 26, 10];
    if (b.length < 8 || signature.some((v, i) => b[i] !== v)) throw new Error('not a PNG (signature)');
    let offset = 8, width = 0, height = 0, channels = 0;
    const idat = [];
    while (offset + 8 <= b.length) {
        const length = b.readUInt32BE(offset), type = b.toString('latin1', offset + 4, offset + 8);
        const data = b.subarray(offset + 8, offset + 8 + length);
        if (type === 'IHDR') {
            width = data.readUInt32BE(0);
            height = data.readUInt32BE(4);
            const depth = data[8], color = data[9];
            if (depth !== 8 || (color !== 2 && color !== 6) || data[12] !== 0)
                throw new Error(`unsupported PNG (bit depth ${depth}, colour type ${color}, interlace ${data[12]})`);
            channels = color === 6 ? 4 : 3;
        } else if (type === 'IDAT') {
            idat.push(data);
        } else if (type === 'IEND') {
            break;
        }
        offset += 12 + length;
    }
    if (!width || !height) throw new Error('no IHDR');
    const raw = zlib.inflateSync(Buffer.concat(idat));
    const stride = width * channels;
    if (raw.length !== height * (stride + 1))
        throw new Error(`inflated ${raw.length} bytes, expected ${height * (stride + 1)}`);
    const pixels = new Uint8Array(height * stride);
    for (let y = 0; y < height; ++y) {
        const filter = raw[y * (stride + 1)];
        const line = raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1));
        const out = y * stride, up = (y - 1) * stride;
        for (let x = 0; x < stride; ++x) {
            const a = x >= channels ? pixels[out + x - channels] : 0;
            const u = y > 0 ? pixels[up + x] : 0;
            const c = x >= channels && y > 0 ? pixels[up + x - channels] : 0;
            let v;
            if (filter === 0) v = line[x];
            else if (filter === 1) v = line[x] + a;
            else if (filter === 2) v = line[x] + u;
            else if (filter === 3) v = line[x] + ((a + u) >> 1);
            else if (filter === 4) {
                const p = a + u - c, pa = Math.abs(p - a), pb = Math.abs(p - u), pc = Math.abs(p - c);
                v = line[x] + (pa <= pb && pa <= pc ? a : pb <= pc ? u : c);
            } else throw new Error(`scanline ${y} has filter ${filter}`);
            pixels[out + x] = v & 255;
        }
    }
    return { width, height, channels, pixels };
}

export function checkMaterials(document, problems) {
    const root = document.getRoot();
    const users = new Map();  // material -> primitives
    for (const mesh of root.listMeshes())
        for (const prim of mesh.listPrimitives()) {
            const m = prim.getMaterial();
            if (!m) continue;
            if (!users.has(m)) users.set(m, []);
            users.get(m).push({ mesh: mesh.getName(), prim });
        }
    const result = { materials: root.listMaterials().length, textured_materials: 0, cutout_materials: 0,
                     images: root.listTextures().length };
    for (const material of root.listMaterials()) {
        const name = `material '${material.getName()}'`;
        const texture = material.getBaseColorTexture();
        if (!texture) continue;
        result.textured_materials += 1;
        if (material.getAlphaMode() === 'MASK') result.cutout_materials += 1;
        if (texture.getMimeType() !== 'image/png')
            problems.push(`${name}: baseColorTexture is ${texture.getMimeType()}, expected image/png`);
        const image = texture.getImage();
        if (!image || image.length === 0) {
            problems.push(`${name}: baseColorTexture has no image data`);
            continue;
        }
        let png;
        try {
            png = decodePng(image);
        } catch (e) {
            problems.push(`${name}: baseColorTexture does not decode: ${e.message}`);
            continue;
        }
        const size = texture.getSize();
        if (!size || size[0] !== png.width || size[1] !== png.height)
            problems.push(`${name}: glTF-Transform reads the image as ${size}, it decodes to ${png.width}x${png.height}`);
        const info = material.getBaseColorTextureInfo();
        if (info.getTexCoord() !== 0) problems.push(`${name}: baseColorTexture uses texCoord ${info.getTexCoord()}`);
        if (info.getWrapS() !== kRepeat || info.getWrapT() !== kRepeat)
            problems.push(`${name}: the sampler does not repeat (wrapS ${info.getWrapS()}, wrapT ${info.getWrapT()})`);
        let transparent = false;
        if (png.channels === 4)
            for (let i = 3; i < png.pixels.length; i += 4) if (png.pixels[i] < 128) { transparent = true; break; }
        if (transparent !== (material.getAlphaMode() === 'MASK'))
            problems.push(`${name}: alphaMode ${material.getAlphaMode()} but the texture ` +
                          (transparent ? 'has cut-out pixels' : 'is opaque'));
        for (const { mesh, prim } of users.get(material) || []) {
            const uv = prim.getAttribute('TEXCOORD_0'), pos = prim.getAttribute('POSITION');
            if (!uv) problems.push(`${name}: mesh '${mesh}' uses its texture without TEXCOORD_0`);
            else if (uv.getType() !== 'VEC2' || !pos || uv.getCount() !== pos.getCount())
                problems.push(`${name}: mesh '${mesh}' TEXCOORD_0 is ${uv.getType()} x ${uv.getCount()}, ` +
                              `POSITION x ${pos ? pos.getCount() : 0}`);
        }
    }
    return result;
}
