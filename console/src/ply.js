// Reads the daemon's preview meshes (GET …/preview): binary little-endian PLY with float
// positions, an optional float per-vertex "displacement", and triangles as uchar-counted uint lists.

const SIZES = { char: 1, uchar: 1, short: 2, ushort: 2, int: 4, uint: 4, float: 4, double: 8 };

function readValue(view, type, at) {
  switch (type) {
    case 'float': return view.getFloat32(at, true);
    case 'double': return view.getFloat64(at, true);
    case 'uchar': return view.getUint8(at);
    case 'char': return view.getInt8(at);
    case 'ushort': return view.getUint16(at, true);
    case 'short': return view.getInt16(at, true);
    case 'uint': return view.getUint32(at, true);
    default: return view.getInt32(at, true);
  }
}

function parseHeader(text) {
  const elements = [];
  for (const line of text.split('\n')) {
    const words = line.trim().split(/\s+/);
    if (words[0] === 'format' && words[1] !== 'binary_little_endian') throw new Error('not a binary little-endian PLY');
    if (words[0] === 'element') elements.push({ name: words[1], count: Number(words[2]), properties: [] });
    if (words[0] === 'property') {
      const element = elements[elements.length - 1];
      if (words[1] === 'list') element.properties.push({ list: true, countType: words[2], type: words[3], name: words[4] });
      else element.properties.push({ type: words[1], name: words[2] });
    }
  }
  return elements;
}

export function parsePreviewPly(buffer) {
  const bytes = new Uint8Array(buffer);
  const head = new TextDecoder().decode(bytes.subarray(0, Math.min(bytes.length, 4096)));
  const end = head.indexOf('end_header\n');
  if (!head.startsWith('ply') || end < 0) throw new Error('not a PLY file');
  const elements = parseHeader(head.slice(0, end));
  const view = new DataView(buffer);
  let at = end + 'end_header\n'.length;
  const out = { positions: null, displacement: null, indices: null };
  for (const element of elements) {
    if (element.name === 'vertex') {
      out.positions = new Float32Array(element.count * 3);
      const hasDisplacement = element.properties.some((p) => p.name === 'displacement');
      if (hasDisplacement) out.displacement = new Float32Array(element.count);
      for (let i = 0; i < element.count; i++) {
        for (const p of element.properties) {
          const v = readValue(view, p.type, at);
          at += SIZES[p.type];
          if (p.name === 'x') out.positions[3 * i] = v;
          else if (p.name === 'y') out.positions[3 * i + 1] = v;
          else if (p.name === 'z') out.positions[3 * i + 2] = v;
          else if (p.name === 'displacement') out.displacement[i] = v;
        }
      }
    } else if (element.name === 'face') {
      const p = element.properties[0];
      out.indices = new Uint32Array(element.count * 3);
      for (let f = 0; f < element.count; f++) {
        const n = readValue(view, p.countType, at);
        at += SIZES[p.countType];
        if (n !== 3) throw new Error('a preview face is not a triangle');
        for (let k = 0; k < 3; k++) { out.indices[3 * f + k] = readValue(view, p.type, at); at += SIZES[p.type]; }
      }
    }
  }
  return out;
}
