// First start only (empty mongo-data volume): the image runs this with mongosh (mongo:4.4: mongo) as root.
// 1. the account the oracle services use: readWrite on the NEEM database only (authSource admin);
// 2. KnowRob 2.x's `one` collection: every mongolog query is an aggregate on it, and a read-only
//    KnowRob does not create it. Same document as KnowRob's initialize_one_db (doubles are Decimal128).
// mongosh has process.env and Node's fs; the legacy `mongo` shell of mongo:4.4 (for CPUs without
// AVX) has _getEnv and cat. The password comes from the compose secret file NEEM_APP_PASSWORD_FILE
// names (NEEM_APP_PASSWORD, the password itself, is accepted for a hand-made setup).
const legacy = typeof process === "undefined" || !process.env;
const getEnv = (name) => (legacy ? _getEnv(name) : process.env[name]) || "";
const readFile = (path) => (legacy ? cat(path) : require("fs").readFileSync(path, "utf8"));
const dbName = getEnv("NEEM_DB") || "roslog";
const appUser = getEnv("NEEM_APP_USER");
const passwordFile = getEnv("NEEM_APP_PASSWORD_FILE");
const appPassword = passwordFile ? readFile(passwordFile).replace(/\r?\n$/, "") : getEnv("NEEM_APP_PASSWORD");
if (!appUser || !appPassword) {
  throw new Error("NEEM_APP_USER and NEEM_APP_PASSWORD_FILE (a file holding the password) must be set");
}

const admin = db.getSiblingDB("admin");
if (admin.getUser(appUser) === null) {
  admin.createUser({ user: appUser, pwd: appPassword, roles: [{ role: "readWrite", db: dbName }] });
  print(`neem-oracle: created user ${appUser} (readWrite on ${dbName})`);
}

const neems = db.getSiblingDB(dbName);
if (neems.getCollection("one").countDocuments({}) === 0) {
  neems.getCollection("one").insertOne({
    v_scope: { time: { since: NumberDecimal("0"), until: NumberDecimal("Infinity") } },
  });
  print(`neem-oracle: created ${dbName}.one`);
}
