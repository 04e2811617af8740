// Shared by read.mjs and write.mjs: the codecs @mcap/core needs (it brings none of its own) and
// a CRC-32 of our own (zlib's polynomial) for the checks @mcap/core does not make.
import lz4Decompress from "@foxglove/wasm-lz4";
import zstd from "@foxglove/wasm-zstd";
import lz4js from "lz4js";

export async function loadCodecs() {
  await zstd.isLoaded;
  await lz4Decompress.isLoaded;
  return {
    decompressHandlers: {
      zstd: (buffer, size) => new Uint8Array(zstd.decompress(buffer, Number(size))),
      lz4: (buffer, size) => new Uint8Array(lz4Decompress(buffer, Number(size))),
    },
    compressors: {
      zstd: (data) => ({ compression: "zstd", compressedData: new Uint8Array(zstd.compress(data)) }),
      // lz4js writes the LZ4 frame format, which the MCAP registry's "lz4" means.
      lz4: (data) => ({ compression: "lz4", compressedData: new Uint8Array(lz4js.compress(data)) }),
    },
  };
}

const TABLE = (() => {
  const t = new Uint32Array(256);
  for (let b = 0; b < 256; b++) {
    let c = b;
    for (let k = 0; k < 8; k++) c = c & 1 ? (c >>> 1) ^ 0xedb88320 : c >>> 1;
    t[b] = c >>> 0;
  }
  return t;
})();

/** An incremental CRC-32: update(bytes) any number of times, then value(). */
export class Crc32 {
  #c = 0xffffffff;
  update(bytes) {
    let c = this.#c;
    for (let i = 0; i < bytes.length; i++) c = TABLE[(c ^ bytes[i]) & 0xff] ^ (c >>> 8);
    this.#c = c >>> 0;
    return this;
  }
  value() {
    return (this.#c ^ 0xffffffff) >>> 0;
  }
}

export const crc32 = (bytes) => new Crc32().update(bytes).value();

/** JSON with bigints as decimal strings and Maps as objects. */
export function toJson(value) {
  return JSON.stringify(
    value,
    (_, v) => {
      if (typeof v === "bigint") return v.toString();
      if (v instanceof Map) return Object.fromEntries(v);
      return v;
    },
    1,
  );
}
