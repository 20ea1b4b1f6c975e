// Just enough ZIP for the console: list the names in a ZIP a user drops (to find its main mesh's
// format), and pack a dropped folder into a stored (uncompressed) ZIP the daemon reads whole.

const CRC_TABLE = (() => {
  const table = new Uint32Array(256);
  for (let n = 0; n < 256; n++) {
    let c = n;
    for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
    table[n] = c >>> 0;
  }
  return table;
})();

function crc32(bytes) {
  let c = 0xffffffff;
  for (let i = 0; i < bytes.length; i++) c = CRC_TABLE[(c ^ bytes[i]) & 0xff] ^ (c >>> 8);
  return (c ^ 0xffffffff) >>> 0;
}

// The names of the files in a ZIP, from its central directory.
export function zipEntryNames(buffer) {
  const view = new DataView(buffer);
  for (let at = buffer.byteLength - 22; at >= Math.max(0, buffer.byteLength - 65557); at--) {
    if (view.getUint32(at, true) !== 0x06054b50) continue;
    const count = view.getUint16(at + 10, true);
    let entry = view.getUint32(at + 16, true);
    const names = [];
    for (let i = 0; i < count && entry + 46 <= buffer.byteLength; i++) {
      const nameLength = view.getUint16(entry + 28, true);
      const extra = view.getUint16(entry + 30, true), comment = view.getUint16(entry + 32, true);
      names.push(new TextDecoder().decode(new Uint8Array(buffer, entry + 46, nameLength)));
      entry += 46 + nameLength + extra + comment;
    }
    return names;
  }
  throw new Error('this is not a ZIP file');
}

// files: [{name, bytes: Uint8Array}] → a Blob of a ZIP that stores them as they are.
export function storedZip(files) {
  const encoder = new TextEncoder();
  const parts = [], central = [];
  let offset = 0;
  for (const file of files) {
    const name = encoder.encode(file.name);
    const crc = crc32(file.bytes);
    const local = new DataView(new ArrayBuffer(30));
    local.setUint32(0, 0x04034b50, true); local.setUint16(4, 20, true); local.setUint16(6, 0x0800, true);
    local.setUint32(14, crc, true); local.setUint32(18, file.bytes.length, true); local.setUint32(22, file.bytes.length, true);
    local.setUint16(26, name.length, true);
    const record = new DataView(new ArrayBuffer(46));
    record.setUint32(0, 0x02014b50, true); record.setUint16(4, 20, true); record.setUint16(6, 20, true);
    record.setUint16(8, 0x0800, true); record.setUint32(16, crc, true);
    record.setUint32(20, file.bytes.length, true); record.setUint32(24, file.bytes.length, true);
    record.setUint16(28, name.length, true); record.setUint32(42, offset, true);
    parts.push(local, name, file.bytes);
    central.push(record, name);
    offset += 30 + name.length + file.bytes.length;
  }
  const centralSize = central.reduce((n, part) => n + part.byteLength, 0);
  const end = new DataView(new ArrayBuffer(22));
  end.setUint32(0, 0x06054b50, true); end.setUint16(8, files.length, true); end.setUint16(10, files.length, true);
  end.setUint32(12, centralSize, true); end.setUint32(16, offset, true);
  return new Blob([...parts, ...central, end], { type: 'application/zip' });
}
