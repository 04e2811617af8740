// Reads an MCAP file with the reference implementation and prints what it found as JSON:
//   node read.mjs FILE
// "indexed": McapIndexedReader (summary, chunk indexes, summary CRC, chunk CRCs, attachment
// CRCs), every message in log-time order; "stream": McapStreamReader over every record of the
// file (chunk and attachment CRCs). Both report the data-section CRC checked against the bytes,
// which @mcap/core itself does not check. Exits 1 with the error on stderr if either fails.
import { McapIndexedReader, McapStreamReader } from "@mcap/core";
import { readFileSync } from "node:fs";

import { Crc32, crc32, loadCodecs, toJson } from "./common.mjs";

const path = process.argv[2];
if (!path) {
  console.error("usage: node read.mjs FILE");
  process.exit(2);
}
const bytes = new Uint8Array(readFileSync(path));
const { decompressHandlers } = await loadCodecs();

async function readIndexed() {
  const readable = {
    size: async () => BigInt(bytes.length),
    read: async (offset, size) => bytes.subarray(Number(offset), Number(offset + size)),
  };
  let reader;
  try {
    reader = await McapIndexedReader.Initialize({ readable, decompressHandlers });
  } catch (e) {
    if (String(e.message).includes("File is not indexed")) return { indexed: false };
    throw e;
  }
  const schemas = [...reader.schemasById.values()].map((s) => ({
    id: s.id,
    name: s.name,
    encoding: s.encoding,
    dataCrc: crc32(s.data),
  }));
  const channels = [...reader.channelsById.values()].map((c) => ({
    id: c.id,
    topic: c.topic,
    schemaId: c.schemaId,
    messageEncoding: c.messageEncoding,
    metadata: c.metadata,
    schemaFound: c.schemaId === 0 || reader.schemasById.has(c.schemaId),
  }));
  const perTopic = {};
  const ordered = new Crc32();
  let messages = 0;
  let last = -1n;
  let inOrder = true;
  for await (const m of reader.readMessages({ validateCrcs: true })) {
    const topic = reader.channelsById.get(m.channelId).topic;
    perTopic[topic] = (perTopic[topic] ?? 0) + 1;
    ordered.update(m.data);
    if (m.logTime < last) inOrder = false;
    last = m.logTime;
    messages++;
  }
  const metadata = [];
  for await (const m of reader.readMetadata()) metadata.push({ name: m.name, metadata: m.metadata });
  const attachments = [];
  for await (const a of reader.readAttachments({ validateCrcs: true })) {
    attachments.push({ name: a.name, mediaType: a.mediaType, size: a.data.length, crc: crc32(a.data) });
  }
  const dataCrc = crc32(bytes.subarray(0, Number(reader.dataEndOffset)));
  return {
    indexed: true,
    profile: reader.header.profile,
    library: reader.header.library,
    schemas,
    channels,
    statistics: reader.statistics,
    chunkIndexes: reader.chunkIndexes.length,
    compressions: [...new Set(reader.chunkIndexes.map((c) => c.compression))].sort(),
    summaryOffsets: [...reader.summaryOffsetsByOpcode.keys()].sort((a, b) => a - b),
    messages,
    perTopic,
    inOrder,
    orderedDataCrc: ordered.value(),
    metadata,
    attachments,
    dataSectionCrcOk: reader.dataSectionCrc === undefined ? null : reader.dataSectionCrc === dataCrc,
  };
}

function readStream() {
  const reader = new McapStreamReader({ includeChunks: true, decompressHandlers, validateCrcs: true });
  reader.append(bytes);
  const records = {};
  let messages = 0;
  let sumOfDataCrcs = 0;
  let dataEndCrc;
  let offset = 0;
  for (let r; (r = reader.nextRecord()); ) {
    records[r.type] = (records[r.type] ?? 0) + 1;
    if (r.type === "Message") {
      messages++;
      sumOfDataCrcs = (sumOfDataCrcs + crc32(r.data)) >>> 0;
    }
    if (r.type === "DataEnd") dataEndCrc = r.dataSectionCrc;
  }
  if (!reader.done()) throw new Error("the stream reader did not reach the end of the file");
  // The DataEnd record is the last of the data section: find it from the footer's side.
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const footerAt = bytes.length - 8 - 29;
  const summaryStart = Number(view.getBigUint64(footerAt + 9, true));
  offset = summaryStart !== 0 ? summaryStart - 13 : footerAt - 13;
  const dataCrc = crc32(bytes.subarray(0, offset));
  return {
    done: reader.done(),
    records,
    messages,
    sumOfDataCrcs,
    dataSectionCrcOk: dataEndCrc === 0 ? null : dataEndCrc === dataCrc,
  };
}

try {
  const indexed = await readIndexed();
  const stream = readStream();
  console.log(toJson({ file: path, size: bytes.length, indexed, stream }));
} catch (e) {
  console.error(`read.mjs: ${path}: ${e.message}`);
  process.exit(1);
}
