"""Study mode: a protocol of conditions run with a participant through the console, questionnaires after each
condition, every episode recorded, fluency measured from the recordings, and the tables across participants."""
