// Reads an MCAP file with the reference TypeScript reader (@mcap/core), twice:
//  - McapIndexedReader: footer -> summary -> chunk indexes -> message indexes -> chunks, i.e. the
//    way Foxglove seeks in a file; it proves the summary and indexes are right;
//  - McapStreamReader: every record from the start, checking chunk CRCs.
// Prints {"topics": {topic: count}, "schemas": [names], "messages": N} and exits 0 only if both
// readings agree with each other and with the file's Statistics record.
//
// Usage: node read_mcap.mjs FILE.mcap

import { readFile } from "node:fs/promises";
import { isDeepStrictEqual } from "node:util";

import lz4 from "@foxglove/wasm-lz4";
import * as zstd from "@foxglove/wasm-zstd";
import { McapIndexedReader, McapStreamReader } from "@mcap/core";

const decompressHandlers = {
  zstd: (buffer, decompressedSize) => zstd.decompress(buffer, Number(decompressedSize)),
  lz4: (buffer, decompressedSize) => lz4(buffer, Number(decompressedSize)),
};

function summarize(countsByTopic, schemaNames) {
  const topics = {};
  for (const topic of [...countsByTopic.keys()].sort()) topics[topic] = countsByTopic.get(topic);
  let messages = 0;
  for (const count of countsByTopic.values()) messages += count;
  return { topics, schemas: [...new Set(schemaNames)].sort(), messages };
}

function count(map, key) {
  map.set(key, (map.get(key) ?? 0) + 1);
}

async function readIndexed(bytes) {
  const readable = {
    size: async () => BigInt(bytes.length),
    read: async (offset, length) => {
      const end = offset + length;
      if (offset < 0n || end > BigInt(bytes.length)) {
        throw new Error(`read of ${length} bytes at ${offset} is outside the file`);
      }
      return bytes.subarray(Number(offset), Number(end));
    },
  };
  const reader = await McapIndexedReader.Initialize({ readable, decompressHandlers });
  if (reader.chunkIndexes.length === 0) throw new Error("indexed reader: no chunk indexes");
  const counts = new Map();
  let lastLogTime = -1n;
  for await (const message of reader.readMessages()) {
    if (message.logTime < lastLogTime) throw new Error("indexed reader: messages out of log-time order");
    lastLogTime = message.logTime;
    const channel = reader.channelsById.get(message.channelId);
    if (!channel) throw new Error(`indexed reader: unknown channel ${message.channelId}`);
    count(counts, channel.topic);
  }
  const stats = reader.statistics;
  if (!stats) throw new Error("indexed reader: no Statistics record");
  let total = 0;
  for (const [channelId, n] of stats.channelMessageCounts) {
    const topic = reader.channelsById.get(channelId)?.topic;
    if ((counts.get(topic) ?? 0) !== Number(n)) {
      throw new Error(`Statistics says ${n} messages on channel ${channelId}, read ${counts.get(topic)}`);
    }
    total += Number(n);
  }
  if (Number(stats.messageCount) !== total) {
    throw new Error(`Statistics message_count ${stats.messageCount} != sum of channel counts ${total}`);
  }
  if (Number(stats.chunkCount) !== reader.chunkIndexes.length) {
    throw new Error(`Statistics chunk_count ${stats.chunkCount} != ${reader.chunkIndexes.length} chunk indexes`);
  }
  const schemaNames = [...reader.schemasById.values()].map((s) => s.name);
  return summarize(counts, schemaNames);
}

function readStreamed(bytes) {
  const reader = new McapStreamReader({ decompressHandlers, validateCrcs: true });
  reader.append(bytes);
  const topicsByChannel = new Map();
  const schemaNames = [];
  const counts = new Map();
  for (let record; (record = reader.nextRecord()); ) {
    switch (record.type) {
      case "Schema":
        schemaNames.push(record.name);
        break;
      case "Channel":
        topicsByChannel.set(record.id, record.topic);
        break;
      case "Message": {
        const topic = topicsByChannel.get(record.channelId);
        if (topic === undefined) throw new Error(`stream reader: unknown channel ${record.channelId}`);
        count(counts, topic);
        break;
      }
      default:
        break;
    }
  }
  if (!reader.done()) throw new Error("stream reader: file ended before the footer and magic");
  return summarize(counts, schemaNames);
}

async function main() {
  const [path] = process.argv.slice(2);
  if (!path) {
    console.error("usage: node read_mcap.mjs FILE.mcap");
    process.exit(2);
  }
  await Promise.all([zstd.isLoaded, lz4.isLoaded]);
  const bytes = new Uint8Array(await readFile(path));
  const indexed = await readIndexed(bytes);
  const streamed = readStreamed(bytes);
  if (!isDeepStrictEqual(indexed, streamed)) {
    throw new Error(
      `indexed and stream readers disagree:\n  indexed  ${JSON.stringify(indexed)}\n  streamed ${JSON.stringify(streamed)}`,
    );
  }
  console.log(JSON.stringify(indexed));
}

main().catch((error) => {
  console.error(`read_mcap.mjs: ${process.argv[2] ?? ""}: ${error.message ?? error}`);
  process.exit(1);
});
