"""The semantic core every package shares: vocabulary, tasks, layouts, features, geometry, rules. numpy only."""
